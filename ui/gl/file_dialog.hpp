// A small ImGui file chooser (modal): browse folders, pick or type a file name. What clicks and keys do is
// FileBrowser's (ui/model/file_browser.hpp): a single click selects, a double click or Enter opens.
#pragma once
#include "ui/model/file_browser.hpp"

#include <functional>
#include <string>
#include <vector>

namespace sonarsim::ui {

/// This frame's input as the dialog needs it, from the viewer's event stream (ImGui 1.86 polls once a frame
/// and misses a double click, or a key tap, shorter than a slow frame).
struct DialogInput {
    bool double_clicked = false; ///< a left double click (GlfwInput::double_clicked())
    bool enter = false, up = false, down = false;
};

class FileDialog {
  public:
    /// Opens the dialog on the next draw(). `extensions` (lower case, with the dot) filter the listing.
    /// `accept` (optional) further filters files by path (e.g. scene files, not render metadata).
    void open(const std::string& title, bool save, std::vector<std::string> extensions,
              const std::string& start_dir, std::function<bool(const std::string&)> accept = {});
    /// Opens it on the next draw() to choose a folder: folders only, no name field; the path returned is the
    /// folder shown when the user confirms.
    void open_folder(const std::string& title, const std::string& start_dir);
    /// Closes it without a choice (Escape).
    void close() { close_ = open_ || visible_; }
    /// Draws it while open; returns true once, when the user confirms, with the chosen path in `path`.
    bool draw(std::string& path, const DialogInput& in);
    bool is_open() const { return open_ || visible_; }

  private:
    std::string title_, dir_field_;
    FileBrowser browser_;
    bool close_ = false;
    bool save_ = false, folder_ = false, open_ = false, visible_ = false;
    bool focus_name_ = false; ///< a Save dialog's name field takes the keyboard when it appears
    bool scroll_to_selected_ = false;
    bool name_active_ = false; ///< the name field had the keyboard last frame
};

} // namespace sonarsim::ui

// A small ImGui file chooser (modal): browse folders, pick or type a file name.
#pragma once
#include <functional>
#include <string>
#include <vector>

namespace sonarsim::ui {

class FileDialog {
  public:
    /// Opens the dialog on the next draw(). `extensions` (lower case, with the dot) filter the listing.
    /// `accept` (optional) further filters files by path (e.g. scene files, not render metadata).
    void open(const std::string& title, bool save, std::vector<std::string> extensions,
              const std::string& start_dir, std::function<bool(const std::string&)> accept = {});
    /// Closes it without a choice (Escape).
    void close() { close_ = open_ || visible_; }
    /// Draws it while open; returns true once, when the user confirms, with the chosen path in `path`.
    bool draw(std::string& path);
    bool is_open() const { return open_ || visible_; }

  private:
    std::string title_, dir_, name_;
    std::vector<std::string> ext_;
    std::function<bool(const std::string&)> accept_;
    bool close_ = false;
    bool save_ = false, open_ = false, visible_ = false;
};

} // namespace sonarsim::ui

// The Open/Save dialog's logic, GL-free (ui/gl/file_dialog.cpp draws it): the listing of one folder, and what
// clicks and keys do. As in any file dialog: a single click selects (a file fills the name field); a double
// click or Enter opens, which enters a folder and chooses a file. Unit-tested in tests/ui.
#pragma once
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace sonarsim::ui {

struct FileEntry {
    std::string name; ///< file name, "../" for the parent, folders end in '/'
    bool folder = false;
};

class FileBrowser {
  public:
    /// Lists `dir` (absolute, normalised). `extensions` (lower case, with the dot) filter the files; `accept`
    /// (optional) further filters them by path.
    void open(const std::string& dir, std::vector<std::string> extensions,
              std::function<bool(const std::string&)> accept = {});
    /// Lists `dir` (typed in the folder field, or entered); the selection is cleared.
    void set_dir(const std::string& dir);
    const std::string& dir() const { return dir_; }
    /// "../" first, then folders, then files, each by name.
    const std::vector<FileEntry>& entries() const { return entries_; }
    int selected() const { return selected_; }
    /// The file name field (typed, or filled by selecting a file).
    std::string name;

    /// A single click on entry i: selects it; a file also fills the name field. Never opens anything.
    void click(size_t i);
    /// A double click on entry i (or Enter with it selected): a folder is entered; a file is chosen (its
    /// path returned).
    std::optional<std::string> activate(size_t i);
    /// Enter, or the Open/Save button: the selected folder is entered; otherwise the name field is chosen
    /// (relative to the folder, or absolute); nothing when it is empty.
    std::optional<std::string> confirm();
    /// Enter in the name field: the typed name (relative to the folder, or absolute); nothing when empty.
    std::optional<std::string> typed() const;
    /// Arrow keys: moves the selection by `delta` entries (clamped), as a click would.
    void move_selection(int delta);

  private:
    void list();
    std::string dir_;
    std::vector<std::string> ext_;
    std::function<bool(const std::string&)> accept_;
    std::vector<FileEntry> entries_;
    int selected_ = -1;
};

} // namespace sonarsim::ui

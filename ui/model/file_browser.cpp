#include "ui/model/file_browser.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace fs = std::filesystem;

namespace sonarsim::ui {
namespace {

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

} // namespace

void FileBrowser::open(const std::string& dir, std::vector<std::string> extensions,
                       std::function<bool(const std::string&)> accept) {
    ext_ = std::move(extensions), accept_ = std::move(accept);
    name.clear();
    set_dir(dir);
}

void FileBrowser::set_dir(const std::string& dir) {
    std::error_code ec;
    dir_ = fs::absolute(dir.empty() ? "." : dir, ec).lexically_normal().string();
    if (dir_.size() > 1 && dir_.back() == '/') dir_.pop_back();
    selected_ = -1;
    list();
}

void FileBrowser::list() {
    entries_.clear();
    std::vector<FileEntry> folders, files;
    std::error_code ec;
    for (fs::directory_iterator it(dir_, fs::directory_options::skip_permission_denied, ec), end;
         !ec && it != end; it.increment(ec)) {
        const std::string n = it->path().filename().string();
        if (n.empty() || n[0] == '.') continue;
        std::error_code ec2;
        if (it->is_directory(ec2)) {
            folders.push_back({n + "/", true});
        } else if (ext_.empty() || std::find(ext_.begin(), ext_.end(),
                                             lower(it->path().extension().string())) != ext_.end()) {
            if (!accept_ || accept_(it->path().string())) files.push_back({n, false});
        }
    }
    auto by_name = [](const FileEntry& a, const FileEntry& b) { return a.name < b.name; };
    std::sort(folders.begin(), folders.end(), by_name);
    std::sort(files.begin(), files.end(), by_name);
    if (fs::path(dir_).has_parent_path() && fs::path(dir_) != fs::path(dir_).root_path())
        entries_.push_back({"../", true});
    entries_.insert(entries_.end(), folders.begin(), folders.end());
    entries_.insert(entries_.end(), files.begin(), files.end());
}

void FileBrowser::click(size_t i) {
    if (i >= entries_.size()) return;
    selected_ = int(i);
    if (!entries_[i].folder) name = entries_[i].name;
}

std::optional<std::string> FileBrowser::activate(size_t i) {
    if (i >= entries_.size()) return std::nullopt;
    const FileEntry e = entries_[i];
    if (e.folder) {
        set_dir(e.name == "../" ? fs::path(dir_).parent_path().string() : (fs::path(dir_) / e.name).string());
        return std::nullopt;
    }
    name = e.name;
    return (fs::path(dir_) / e.name).string();
}

std::optional<std::string> FileBrowser::confirm() {
    if (selected_ >= 0 && size_t(selected_) < entries_.size() && entries_[size_t(selected_)].folder)
        return activate(size_t(selected_));
    return typed();
}

std::optional<std::string> FileBrowser::typed() const {
    if (name.empty()) return std::nullopt;
    const fs::path p(name);
    return p.is_absolute() ? p.string() : (fs::path(dir_) / p).string();
}

void FileBrowser::move_selection(int delta) {
    if (entries_.empty()) return;
    const int from = selected_ < 0 ? (delta > 0 ? -1 : int(entries_.size())) : selected_;
    click(size_t(std::clamp(from + delta, 0, int(entries_.size()) - 1)));
}

} // namespace sonarsim::ui

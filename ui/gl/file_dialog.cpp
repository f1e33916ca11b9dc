#include "ui/gl/file_dialog.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <imgui.h>
#include <imgui_stdlib.h>

namespace fs = std::filesystem;

namespace sonarsim::ui {
namespace {

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

} // namespace

void FileDialog::open(const std::string& title, bool save, std::vector<std::string> extensions,
                      const std::string& start_dir, std::function<bool(const std::string&)> accept) {
    title_ = title, save_ = save, ext_ = std::move(extensions), open_ = true, accept_ = std::move(accept);
    close_ = false;
    std::error_code ec;
    dir_ = fs::absolute(start_dir.empty() ? "." : start_dir, ec).lexically_normal().string();
    name_.clear();
}

bool FileDialog::draw(std::string& path) {
    if (open_) {
        ImGui::OpenPopup(title_.c_str());
        open_ = false;
        visible_ = true;
    }
    bool chosen = false;
    ImGui::SetNextWindowSize(ImVec2(560, 420), ImGuiCond_Appearing);
    if (ImGui::BeginPopupModal(title_.c_str(), nullptr)) {
        ImGui::SetNextItemWidth(-1);
        ImGui::InputText("##dir", &dir_);
        std::vector<fs::directory_entry> dirs, files;
        std::error_code ec;
        for (fs::directory_iterator it(dir_, fs::directory_options::skip_permission_denied, ec), end;
             !ec && it != end; it.increment(ec)) {
            const std::string name = it->path().filename().string();
            if (name.empty() || name[0] == '.') continue;
            std::error_code ec2;
            if (it->is_directory(ec2)) {
                dirs.push_back(*it);
            } else if (ext_.empty() || std::find(ext_.begin(), ext_.end(),
                                                 lower(it->path().extension().string())) != ext_.end()) {
                if (!accept_ || accept_(it->path().string())) files.push_back(*it);
            }
        }
        auto by_name = [](const fs::directory_entry& a, const fs::directory_entry& b) {
            return a.path() < b.path();
        };
        std::sort(dirs.begin(), dirs.end(), by_name);
        std::sort(files.begin(), files.end(), by_name);
        ImGui::BeginChild("##list", ImVec2(0, -ImGui::GetFrameHeightWithSpacing() * 2), true);
        if (ImGui::Selectable("../")) dir_ = fs::path(dir_).parent_path().string();
        for (auto& d : dirs)
            if (ImGui::Selectable((d.path().filename().string() + "/").c_str())) dir_ = d.path().string();
        for (auto& f : files) {
            const std::string name = f.path().filename().string();
            if (ImGui::Selectable(name.c_str(), name == name_, ImGuiSelectableFlags_AllowDoubleClick)) {
                name_ = name;
                if (ImGui::IsMouseDoubleClicked(0)) chosen = true;
            }
        }
        ImGui::EndChild();
        ImGui::SetNextItemWidth(-1);
        if (ImGui::InputText("##name", &name_, ImGuiInputTextFlags_EnterReturnsTrue)) chosen = true;
        if (ImGui::Button(save_ ? "Save" : "Open")) chosen = true;
        ImGui::SameLine();
        if (ImGui::Button("Cancel") || close_) {
            visible_ = close_ = false;
            ImGui::CloseCurrentPopup();
        }
        if (chosen && !name_.empty()) {
            const fs::path p(name_);
            path = p.is_absolute() ? p.string() : (fs::path(dir_) / p).string();
            visible_ = false;
            ImGui::CloseCurrentPopup();
        } else {
            chosen = false;
        }
        ImGui::EndPopup();
    } else {
        visible_ = false;
    }
    return chosen;
}

} // namespace sonarsim::ui

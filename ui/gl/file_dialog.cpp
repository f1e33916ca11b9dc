#include "ui/gl/file_dialog.hpp"

#include <imgui.h>
#include <imgui_stdlib.h>
#include <optional>

namespace sonarsim::ui {

void FileDialog::open(const std::string& title, bool save, std::vector<std::string> extensions,
                      const std::string& start_dir, std::function<bool(const std::string&)> accept) {
    title_ = title, save_ = save, open_ = true;
    folder_ = false, focus_name_ = save, close_ = false;
    browser_.open(start_dir, std::move(extensions), std::move(accept));
    dir_field_ = browser_.dir();
}

void FileDialog::open_folder(const std::string& title, const std::string& start_dir) {
    open(title, false, {}, start_dir, [](const std::string&) { return false; }); // lists folders only
    folder_ = true;
}

bool FileDialog::draw(std::string& path, const DialogInput& in) {
    if (open_) {
        ImGui::OpenPopup(title_.c_str());
        open_ = false;
        visible_ = true;
    }
    std::optional<std::string> chosen;
    ImGui::SetNextWindowSize(ImVec2(560, 420), ImGuiCond_Appearing);
    if (ImGui::BeginPopupModal(title_.c_str(), nullptr)) {
        ImGui::SetNextItemWidth(-1);
        if (ImGui::InputText("##dir", &dir_field_, ImGuiInputTextFlags_EnterReturnsTrue))
            browser_.set_dir(dir_field_);
        const bool dir_active = ImGui::IsItemActive();
        ImGui::BeginChild("##list", ImVec2(0, -ImGui::GetFrameHeightWithSpacing() * 2), true);
        const auto& entries = browser_.entries();
        for (size_t i = 0; i < entries.size() && !chosen; ++i) {
            const bool sel = browser_.selected() == int(i);
            const bool clicked = ImGui::Selectable(entries[i].name.c_str(), sel);
            if (in.double_clicked && ImGui::IsItemHovered()) {
                const std::string before = browser_.dir();
                chosen = browser_.activate(i);
                if (browser_.dir() != before) break; // a folder was entered: the listing changed
            } else if (clicked) {
                browser_.click(i);
            }
            if (sel && scroll_to_selected_) ImGui::SetScrollHereY();
        }
        scroll_to_selected_ = false;
        ImGui::EndChild();
        // Keys: Enter opens the selection (or the typed name or folder, in its field), arrows move it.
        if (in.enter && !chosen) {
            if (folder_ && !dir_active && browser_.selected() < 0)
                chosen = browser_.dir();
            else if (name_active_)
                chosen = browser_.typed();
            else if (dir_active)
                browser_.set_dir(dir_field_);
            else
                chosen = browser_.confirm();
        } else if (!dir_active && !name_active_ && (in.up || in.down)) {
            browser_.move_selection(in.down ? 1 : -1), scroll_to_selected_ = true;
        }
        if (!dir_active) dir_field_ = browser_.dir();
        if (folder_) {
            ImGui::TextDisabled("double click or Enter: into a folder; Enter with none selected: this one");
            name_active_ = false;
        } else {
            ImGui::SetNextItemWidth(-1);
            if (focus_name_) ImGui::SetKeyboardFocusHere(), focus_name_ = false; // type a name at once
            if (ImGui::InputText("##name", &browser_.name, ImGuiInputTextFlags_EnterReturnsTrue) && !chosen)
                chosen = browser_.typed();
            name_active_ = ImGui::IsItemActive();
        }
        if (ImGui::Button(folder_ ? "Use this folder" : save_ ? "Save" : "Open"))
            chosen = folder_ ? std::optional(browser_.dir()) : browser_.confirm();
        ImGui::SameLine();
        if (ImGui::Button("Cancel") || close_) {
            visible_ = close_ = false;
            ImGui::CloseCurrentPopup();
        }
        if (chosen) {
            path = *chosen;
            visible_ = false;
            ImGui::CloseCurrentPopup();
        }
        ImGui::EndPopup();
    } else {
        visible_ = false;
    }
    return chosen.has_value();
}

} // namespace sonarsim::ui

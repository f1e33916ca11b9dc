// The menu bar (shortcut labels from bindings.cpp), Help -> Controls (every binding, from bindings.cpp) and
// the file dialogs.
#include "ui/gl/viewer_app.hpp"

#include "ui/model/bindings.hpp"
#include "ui/model/scene_files.hpp"

#include "core/scene/devices.hpp"
#include "core/meshfile/mesh_formats.hpp"

#include <filesystem>
#include <imgui.h>
#include <imgui_internal.h>

namespace sonarsim::ui {

void Viewer::menu_bar() {
    if (!ImGui::BeginMainMenuBar()) return;
    if (ImGui::BeginMenu("File")) {
        if (ImGui::MenuItem("Open scene...", shortcut_text(KeyAction::OpenScene).c_str()))
            ui_.want_open = true;
        if (ImGui::MenuItem("Add mesh...")) ui_.want_add_mesh = true;
        if (ImGui::MenuItem("Save scene as...")) ui_.want_save = true;
        ImGui::Separator();
        if (ImGui::MenuItem("Snapshot", shortcut_text(KeyAction::Snapshot).c_str())) ui_.want_snapshot = true;
        ImGui::MenuItem("Annotated snapshot PNG", nullptr, &ui_.annotated_snapshot);
        bool gt = session_.ground_truth();
        if (ImGui::MenuItem("Ground truth (snapshots, hover)", nullptr, &gt)) session_.set_ground_truth(gt);
        ImGui::Separator();
        if (ImGui::MenuItem("Quit", shortcut_text(KeyAction::Quit).c_str())) quit_ = true;
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Edit")) {
        if (ImGui::MenuItem("Undo", shortcut_text(KeyAction::Undo).c_str(), false, undo_.undo_steps() > 0))
            undo(false);
        if (ImGui::MenuItem("Redo", shortcut_text(KeyAction::Redo).c_str(), false, undo_.redo_steps() > 0))
            undo(true);
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("View")) {
        ImGui::MenuItem("Raw polar image", shortcut_text(KeyAction::TogglePolar).c_str(), &sonar_->polar);
        ImGui::MenuItem("Show traced hits", shortcut_text(KeyAction::ToggleHits).c_str(), &ui_.show_hits);
        if (ImGui::MenuItem("Reset camera", shortcut_text(KeyAction::ResetCamera).c_str())) reset_camera();
        if (ImGui::MenuItem("Measure on the image", shortcut_text(KeyAction::StartMeasure).c_str()))
            sonar_->start_measure();
        ImGui::SetNextItemWidth(ImGui::GetFontSize() * 8);
        ImGui::SliderFloat("UI scale", &ui_.ui_scale, 0.75f, 2.5f, "%.2f");
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Device")) {
        // sonar.device presets (assets/devices) and the sensor model: the same keys as the panel's. The
        // viewer shows imaging sonars: the other kinds' presets render headless.
        const SceneDesc& s = session_.scene();
        for (const std::string& name : device_choices("imaging")) {
            const DevicePreset* p = find_device(name);
            if (ImGui::MenuItem(p ? (name + "  " + p->title).c_str() : "none (keep the values)", nullptr,
                                s.sonar.device == name))
                session_.set("sonar.device", name);
        }
        ImGui::Separator();
        if (ImGui::MenuItem("Ideal sensor", nullptr, s.sensor.model == SensorModel::Ideal))
            session_.set("sensor.model", "ideal");
        if (ImGui::MenuItem("Device sensor (beam patterns, speckle, noise, TVG)", nullptr,
                            s.sensor.model == SensorModel::Device))
            session_.set("sensor.model", "device");
        ImGui::Separator();
        if (ImGui::MenuItem("Multipath (bounces)", shortcut_text(KeyAction::ToggleMultipath).c_str(),
                            s.sampling.bounces > 0))
            toggle_multipath();
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Help")) {
        if (ImGui::MenuItem("Controls")) show_help_ = true;
        ImGui::EndMenu();
    }
    ImGui::EndMainMenuBar();
}

void Viewer::help_window() {
    if (!show_help_) return;
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(vp->Size.x / 2, vp->Size.y / 2), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
    ImGui::SetNextWindowSize(ImVec2(std::min(vp->Size.x - 20, 46 * ImGui::GetFontSize()),
                                    std::min(vp->Size.y - 40, 36 * ImGui::GetFontSize())),
                             ImGuiCond_Appearing);
    if (ImGui::Begin("Mouse and key controls##help", &show_help_, ImGuiWindowFlags_NoCollapse)) {
        if (ImGui::BeginTable("bindings", 3, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp)) {
            ImGui::TableSetupColumn("where");
            ImGui::TableSetupColumn("input");
            ImGui::TableSetupColumn("action");
            ImGui::TableHeadersRow();
            for (const Binding& b : bindings()) {
                ImGui::TableNextRow();
                ImGui::TableNextColumn();
                ImGui::TextUnformatted(b.where);
                ImGui::TableNextColumn();
                ImGui::TextWrapped("%s", b.input.c_str());
                ImGui::TableNextColumn();
                ImGui::TextWrapped("%s", b.action);
            }
            ImGui::EndTable();
        }
    }
    ImGui::End();
}

void Viewer::close_menus() {
    // Escape: menus and popups, the help window, the file dialogs.
    ImGuiContext& g = *ImGui::GetCurrentContext();
    if (g.OpenPopupStack.Size > 0) ImGui::ClosePopupToLevel(0, true);
    show_help_ = false;
    open_dialog_.close();
    mesh_dialog_.close();
    save_dialog_.close();
    snapshot_dir_dialog_.close();
}

void Viewer::dialogs() {
    const std::string dir = session_.scene().source_file.empty()
                                ? "."
                                : std::filesystem::path(session_.scene().source_file).parent_path().string();
    if (ui_.want_open) open_dialog_.open("Open scene", false, {".json"}, dir, looks_like_scene_file);
    if (ui_.want_add_mesh) mesh_dialog_.open("Add mesh", false, mesh_extensions(), dir);
    if (ui_.want_save) save_dialog_.open("Save scene", true, {".json"}, dir);
    if (ui_.want_snapshot_dir) snapshot_dir_dialog_.open_folder("Snapshots go to", ui_.snapshot_dir);
    if (ui_.want_reset_camera) reset_camera();
    ui_.want_open = ui_.want_add_mesh = ui_.want_save = ui_.want_snapshot_dir = ui_.want_reset_camera = false;
    std::string path;
    DialogInput dialog_input;
    dialog_input.double_clicked = input_->double_clicked();
    dialog_input.enter = input_->key_pressed(key::Enter) || input_->key_pressed(key::KeypadEnter);
    dialog_input.up = input_->key_pressed(key::Up), dialog_input.down = input_->key_pressed(key::Down);
    if (open_dialog_.draw(path, dialog_input)) open_files({path});
    if (mesh_dialog_.draw(path, dialog_input)) session_.add_mesh(path);
    if (save_dialog_.draw(path, dialog_input)) session_.save_scene(path);
    if (snapshot_dir_dialog_.draw(path, dialog_input)) ui_.snapshot_dir = path;
}

} // namespace sonarsim::ui

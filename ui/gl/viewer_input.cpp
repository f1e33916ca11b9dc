// Events of one frame in the order they happened: the 3D controller's drags and clicks, key shortcuts (from
// key events, so a tap shorter than a frame counts), undo and redo, dropped files.
#include <epoxy/gl.h>
#include <GLFW/glfw3.h>

#include "ui/gl/viewer_app.hpp"

#include "core/meshfile/mesh_formats.hpp"

#include <algorithm>
#include <imgui.h>

namespace sonarsim::ui {
namespace {

std::string lower_ext(const std::string& path) {
    const size_t dot = path.find_last_of('.');
    std::string e = dot == std::string::npos ? "" : path.substr(dot);
    for (auto& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
    return e;
}

} // namespace

ViewContext Viewer::view_context() const {
    return {session_.scene(), session_.geometry(), layout_.view3d, ImGui::GetIO().WantCaptureMouse};
}

void Viewer::handle_events() {
    controller_.selected = ui_.selected;
    for (const InputEvent& e : input_->take_events()) {
        if (e.type == InputEvent::Type::Key) {
            if (e.key_down && !e.repeat) handle_key(e);
            continue;
        }
        if (auto next = controller_.handle(e, view_context())) apply_edit(*next);
    }
    ui_.selected = controller_.selected;
    controller_.hover(input_->mouse().pos, view_context());
}

void Viewer::apply_edit(const SceneDesc& next) {
    session_.edit([&](SceneDesc& s) { s = next; });
}

void Viewer::handle_key(const InputEvent& e) {
    const Binding* b = key_binding(e.key, e.mods); // the one table (ui/model/bindings.cpp)
    if (!b) return;
    // A text field takes the keys; a dialog too. A slider or a 3D drag held does not.
    const bool typing = ImGui::GetIO().WantTextInput || open_dialog_.is_open() || mesh_dialog_.is_open() ||
                        save_dialog_.is_open() || snapshot_dir_dialog_.is_open();
    if (typing && !b->while_typing) return;
    run_key_action(b->key_action);
}

void Viewer::run_key_action(KeyAction action) {
    switch (action) {
    case KeyAction::None:
        break;
    case KeyAction::Cancel:
        close_menus();
        sonar_->cancel_measure();
        break;
    case KeyAction::Quit:
        quit_ = true;
        break;
    case KeyAction::Undo:
        undo(false);
        break;
    case KeyAction::Redo:
        undo(true);
        break;
    case KeyAction::Snapshot:
        snapshots_.ask(); // every tap is one snapshot, taken once the full-quality image is drawn
        break;
    case KeyAction::TogglePolar:
        sonar_->polar = !sonar_->polar;
        break;
    case KeyAction::ToggleHits:
        ui_.show_hits = !ui_.show_hits;
        break;
    case KeyAction::ResetCamera:
        reset_camera();
        break;
    case KeyAction::OpenScene:
        ui_.want_open = true;
        break;
    case KeyAction::StartMeasure:
        sonar_->start_measure();
        break;
    case KeyAction::ToggleMultipath:
        toggle_multipath();
        break;
    case KeyAction::ToggleRecord:
        trajectory_.toggle_record(session_.scene().sonar.pose);
        break;
    case KeyAction::TogglePlay:
        trajectory_.toggle_play();
        break;
    }
}

void Viewer::toggle_multipath() {
    const int b = session_.scene().sampling.bounces;
    if (b > 0) last_bounces_ = b;
    session_.set("sampling.bounces", b > 0 ? 0 : last_bounces_);
}

void Viewer::record_undo() {
    // One step per completed edit: nothing is recorded while a drag or a slider is held.
    // A trajectory's playback is not an edit: its last pose is recorded once it stops.
    if (interacting_ || controller_.pressed() || trajectory_.playing) return;
    controller_.take_edit_finished();
    undo_.record(session_.scene());
}

void Viewer::undo(bool redo) {
    if (interacting_) return;
    undo_.record(session_.scene()); // an edit not yet recorded (typed this frame) is a step of its own
    const std::optional<SceneDesc> s = redo ? undo_.redo() : undo_.undo();
    if (!s) {
        session_.set_status(redo ? "nothing to redo" : "nothing to undo");
        return;
    }
    const bool other_file = s->source_file != session_.scene().source_file;
    apply_edit(*s);
    if (other_file) update_title();
    session_.set_status(std::string(redo ? "redo" : "undo") + " (" + std::to_string(undo_.undo_steps()) +
                        " more to undo, " + std::to_string(undo_.redo_steps()) + " to redo)");
}

void Viewer::open_files(const std::vector<std::string>& paths) {
    for (const std::string& path : paths) {
        const std::string e = lower_ext(path);
        if (e == ".json") {
            if (session_.open_scene(path)) reset_camera(), update_title();
        } else if (const auto ext = mesh_extensions(); std::find(ext.begin(), ext.end(), e) != ext.end()) {
            session_.add_mesh(path);
        } else {
            session_.set_error(path + ": not a scene (.json) or mesh (" + mesh_extensions_text(" ") + ")");
        }
    }
}

} // namespace sonarsim::ui

#include "ui/model/bindings.hpp"

#include "core/meshfile/mesh_formats.hpp"
#include "ui/model/input_events.hpp"

namespace sonarsim::ui {
namespace {

/// A plain key: runs without Ctrl (Shift and Alt are ignored).
KeyMatch plain(int k) {
    return {k, 0, mods::Control};
}
/// Ctrl + key.
KeyMatch ctrl(int k, int excluded = 0) {
    return {k, mods::Control, excluded};
}

std::vector<Binding> with_key_inputs(std::vector<Binding> rows) {
    for (Binding& b : rows)
        if (b.input.empty())
            for (const KeyMatch& k : b.keys) b.input += (b.input.empty() ? "" : " or ") + key_text(k);
    return rows;
}

} // namespace

const std::vector<Binding>& bindings() {
    using A = KeyAction;
    // A key row's input is its key presses as menus show them ("Ctrl+Shift+Z or Ctrl+Y"), filled in below
    // where the row leaves it empty.
    static const std::vector<Binding> table = with_key_inputs({
        {"3D view", "left-drag (anywhere but the sonar or the selected object; nothing is selected at start)",
         "orbit the camera"},
        {"3D view", "right- or middle-drag", "pan the camera"},
        {"3D view", "wheel", "zoom"},
        {"3D view", "drag the sonar housing or its yellow handle", "move the sonar on the horizontal plane"},
        {"3D view", "Shift+drag sonar", "move the sonar up and down"},
        {"3D view", "Ctrl+drag sonar", "turn the sonar: yaw (left/right), pitch (up/down)"},
        {"3D view", "Ctrl+Shift+drag sonar", "roll the sonar"},
        {"3D view", "Alt with any drag of the sonar", "fine: a tenth of the move or turn"},
        {"3D view", "click an object (or the floor)", "select it for the Object panel (and for dragging)"},
        {"3D view", "drag the selected object",
         "move it on the horizontal plane (terrain: only with Shift or Ctrl)"},
        {"3D view", "Shift+drag object", "move it up and down"},
        {"3D view", "Ctrl+drag object", "turn it: yaw, pitch"},
        {"3D view", "Ctrl+Shift+drag object", "roll it"},
        {"3D view", "Alt+drag object", "scale it (up grows); Alt with Shift or Ctrl: a fine move or turn"},
        {"Sonar image", "hover",
         "elevation arc, echoing points and the strongest echo path (a ghost's mirrors) in 3D, the A-scan of "
         "that beam"},
        {"Sonar image",
         "M, then drag",
         "measure: distance between two points, dB statistics of the box",
         A::StartMeasure,
         {plain(key::M)}},
        {"Keys", "", "snapshot", A::Snapshot, {plain(key::S)}},
        {"Keys", "", "undo the last scene edit", A::Undo, {ctrl(key::Z, mods::Shift)}},
        {"Keys", "", "redo", A::Redo, {{key::Z, mods::Control | mods::Shift}, ctrl(key::Y)}},
        {"Keys", "", "raw polar image / fan", A::TogglePolar, {plain(key::P)}},
        {"Keys", "", "show the traced hits", A::ToggleHits, {plain(key::H)}},
        {"Keys",
         "",
         "multipath on / off: sampling.bounces 0 or its last non-zero value",
         A::ToggleMultipath,
         {plain(key::B)}},
        {"Keys", "", "frame the scene from above, behind the sonar", A::ResetCamera, {plain(key::F)}},
        {"Keys", "", "open a scene", A::OpenScene, {plain(key::O)}},
        {"Keys", "", "start / stop recording the sonar's trajectory", A::ToggleRecord, {plain(key::R)}},
        {"Keys", "", "play / pause the trajectory", A::TogglePlay, {plain(key::Space)}},
        {"Keys", "", "close menus and dialogs, cancel a measurement", A::Cancel, {{key::Escape}}, true},
        {"Keys", "", "quit", A::Quit, {ctrl(key::Q)}},
        {"Sliders", "drag", "change the value"},
        {"Sliders", "Shift+drag", "fine: a tenth of the speed"},
        {"Sliders", "Ctrl+click", "type a value"},
        {"Window", "drop a .json scene or a mesh (" + mesh_extensions_text(" ") + ")", "open it / add it"},
    });
    return table;
}

const Binding* key_binding(int key, int mods) {
    for (const Binding& b : bindings())
        for (const KeyMatch& c : b.keys)
            if (c.matches(key, mods)) return &b;
    return nullptr;
}

std::string key_text(const KeyMatch& keys) {
    std::string s;
    if (keys.required & mods::Control) s += "Ctrl+";
    if (keys.required & mods::Shift) s += "Shift+";
    if (keys.required & mods::Alt) s += "Alt+";
    if (keys.key == key::Space) return s + "Space";
    if (keys.key == key::Escape) return s + "Escape";
    return s + char(keys.key); // letters: their upper-case ASCII code
}

std::string shortcut_text(KeyAction action) {
    for (const Binding& b : bindings())
        if (b.key_action == action && !b.keys.empty()) return key_text(b.keys.front());
    return "";
}

} // namespace sonarsim::ui

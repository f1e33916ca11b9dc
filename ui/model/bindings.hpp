// Every mouse and key binding of the viewer, in one table: Help -> Controls lists it, the viewer dispatches
// its key shortcuts by it (key_action; the actions themselves are in ui/gl/viewer_input.cpp), docs/viewer.md
// documents it (tests/ui checks that it names each one). GL-free.
#pragma once
#include <string>
#include <vector>

namespace sonarsim::ui {

/// What a key shortcut does (run by Viewer::run_key_action).
enum class KeyAction {
    None,
    Cancel, ///< close menus and dialogs, cancel a measurement
    Quit,
    Undo,
    Redo,
    Snapshot,
    TogglePolar,
    ToggleHits,
    ToggleMultipath,
    ResetCamera,
    OpenScene,
    StartMeasure,
    ToggleRecord,
    TogglePlay,
};

/// A key with the modifiers (mods:: bits) it needs and those it must not have; others are ignored.
struct KeyMatch {
    int key = 0;
    int required = 0;
    int excluded = 0;
    bool matches(int k, int mods) const {
        return k == key && (mods & required) == required && !(mods & excluded);
    }
};

struct Binding {
    const char* where; ///< "3D view", "Sonar image", "Keys", "Sliders", "Window"
    std::string input; ///< e.g. "Ctrl+Z"
    const char* action;
    KeyAction key_action = KeyAction::None; ///< what its keys run (None: a mouse binding)
    std::vector<KeyMatch> keys = {};        ///< the presses that run it
    bool while_typing = false;              ///< also while a text field or a file dialog has the keys
};

const std::vector<Binding>& bindings();

/// The binding whose keys match a press of `key` with `mods` (the first in table order), or null.
const Binding* key_binding(int key, int mods);

/// A key press as menus show it: "Ctrl+Shift+Z", "Space", "M".
std::string key_text(const KeyMatch& keys);

/// The first key press that runs `action` (key_text; "" if none), for menu items.
std::string shortcut_text(KeyAction action);

} // namespace sonarsim::ui

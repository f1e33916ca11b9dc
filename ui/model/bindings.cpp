#include "ui/model/bindings.hpp"

namespace sonarsim::ui {

const std::vector<Binding>& bindings() {
    static const std::vector<Binding> table = {
        {"3D view", "left-drag (empty space or floor)", "orbit the camera"},
        {"3D view", "right- or middle-drag", "pan the camera"},
        {"3D view", "wheel", "zoom"},
        {"3D view", "drag the sonar housing or its yellow handle", "move the sonar on the horizontal plane"},
        {"3D view", "Shift+drag sonar", "move the sonar up and down"},
        {"3D view", "Ctrl+drag sonar", "turn the sonar: yaw (left/right), pitch (up/down)"},
        {"3D view", "Ctrl+Shift+drag or Alt+drag sonar", "roll the sonar"},
        {"3D view", "click an object (or the floor)", "select it for the Object panel"},
        {"3D view", "drag an object", "move it on the horizontal plane"},
        {"3D view", "Shift+drag object", "move it up and down"},
        {"3D view", "Ctrl+drag object", "turn it: yaw, pitch"},
        {"3D view", "Ctrl+Shift+drag object", "roll it"},
        {"3D view", "Alt+drag object", "scale it (up grows)"},
        {"Sonar image", "hover",
         "elevation arc, echoing points and the strongest echo path (a ghost's mirrors) in 3D, the A-scan of "
         "that beam"},
        {"Sonar image", "M, then drag", "measure: distance between two points, dB statistics of the box"},
        {"Keys", "S", "snapshot"},
        {"Keys", "Ctrl+Z", "undo the last scene edit"},
        {"Keys", "Ctrl+Shift+Z or Ctrl+Y", "redo"},
        {"Keys", "P", "raw polar image / fan"},
        {"Keys", "H", "show the traced hits"},
        {"Keys", "B", "multipath on / off: sampling.bounces 0 or its last non-zero value"},
        {"Keys", "F", "reset the camera"},
        {"Keys", "O", "open a scene"},
        {"Keys", "R", "start / stop recording the sonar's trajectory"},
        {"Keys", "Space", "play / pause the trajectory"},
        {"Keys", "Escape", "close menus and dialogs, cancel a measurement"},
        {"Keys", "Ctrl+Q", "quit"},
        {"Sliders", "drag", "change the value"},
        {"Sliders", "Shift+drag", "fine: a tenth of the speed"},
        {"Sliders", "Ctrl+click", "type a value"},
        {"Window", "drop a .json scene or a mesh (.obj .ply .stl .off)", "open it / add it"},
    };
    return table;
}

} // namespace sonarsim::ui

// `sonarsim view --script FILE`: timed mouse and key events (and a few actions) replayed through the viewer's
// real event path (the GLFW callbacks). GL-free: parsing, and turning a step into the events GLFW would send.
//
// One step per line, `FRAME COMMAND ARGS...`, frames counted from 0 in non-decreasing order; `#` starts a
// comment. Input: `move X Y`, `move_to KEY FX FY` (to the point at fractions FX, FY of the panel widget of
// parameter KEY as drawn in the frame before, e.g. `move_to sonar.source_level_db 0.3 0.5`; its part on
// screen, an error when none is), `move_by DX DY`,
// `press left|right|middle`, `release left|right|middle`, `click X Y` (move, press, release), `wheel STEPS`,
// `key NAME` (press and release, e.g. `key S`, `key ctrl+shift+z`), `keydown NAME`, `keyup NAME`. Actions:
// `screenshot FILE.png`, `state FILE.json`, `layout FILE.json`, `snapshot PREFIX`, `trajectory_save
// FILE.csv`, `trajectory_load FILE.csv` (as the panel's Load: the sonar goes to the first pose),
// `trajectory_snapshots PREFIX` (playback with one snapshot per pose: PREFIX.K.*), `open FILE` (a scene or
// mesh, as if dropped on the window), `ground_truth on|off` (as File > Ground truth), `quit`. Several steps
// may share a frame: they all arrive before that frame is drawn (a quick click or tap).
#pragma once
#include "ui/model/input_events.hpp"

#include <string>
#include <vector>

namespace sonarsim::ui {

struct ScriptStep {
    int frame = 0;
    std::string command;
    std::vector<std::string> args;
    int line = 0;
};

/// Parses a script; throws InputError(file, "line N", message) on a bad line.
std::vector<ScriptStep> parse_script(const std::string& text, const std::string& file);
std::vector<ScriptStep> load_script(const std::string& path);

/// A key with its modifiers, e.g. "ctrl+shift+z" -> {Z, Control | Shift}. Throws InputError.
struct KeyChord {
    int key = 0;
    int mods = 0;
};
KeyChord parse_key_chord(const std::string& text, const std::string& file, int line);

/// True for commands that produce input events (the rest are actions the viewer runs).
bool is_input_command(const std::string& command);

/// The events a step sends, as GLFW would deliver them (none for move_to, which the viewer resolves): `pos`
/// is the mouse position before the step (updated by moves), `held_mods` the modifier keys held (updated by
/// keydown/keyup of modifiers).
std::vector<InputEvent> step_events(const ScriptStep& step, glm::dvec2& pos, int& held_mods);

} // namespace sonarsim::ui

// Plays `sonarsim view --script` (and the older --mouse and --drag) frame by frame: the input events due
// before a frame is drawn and the actions due after it. GL-free: the viewer injects the events through its
// GLFW callbacks and runs the actions.
#pragma once
#include "ui/model/input_events.hpp"
#include "ui/model/layout.hpp"
#include "ui/model/script.hpp"

#include <array>
#include <glm/glm.hpp>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace sonarsim::ui {

class ScriptPlayer {
  public:
    ScriptPlayer() = default;
    /// `steps` of the script `file` (load_script); `hold_mouse`: the mouse held at a window pixel from the
    /// first frame; `drag`: a left-button drag from one pixel to the other over `frames` frames (at least 4).
    ScriptPlayer(std::vector<ScriptStep> steps, std::string file, std::optional<glm::dvec2> hold_mouse = {},
                 std::optional<std::array<glm::dvec2, 2>> drag = {}, int frames = 0);
    /// The input events due before frame `index` is drawn, as GLFW would deliver them. `widgets`: where each
    /// parameter's panel widget was drawn in the frame before (move_to's targets). Throws InputError naming
    /// the script's file and line for a move_to to a parameter with no widget.
    std::vector<InputEvent> input(int index, const std::map<std::string, Rect>& widgets);
    /// The actions (steps that are not input) due after frame `index` is drawn, in order; each once.
    std::vector<ScriptStep> actions(int index);
    /// Whether an action `command` is due after frame `index` is drawn (actions() not yet taken).
    bool has_action(int index, const std::string& command) const;
    /// The last frame to draw: `frames` - 1 when given, else the script's last frame + 1; -1: none (the
    /// viewer runs until its window closes).
    int last_frame() const { return last_frame_; }
    bool has_script() const { return !steps_.empty(); }

  private:
    std::vector<ScriptStep> steps_;
    std::string file_;
    std::optional<glm::dvec2> hold_mouse_;
    std::optional<std::array<glm::dvec2, 2>> drag_;
    int frames_ = 0, last_frame_ = -1;
    size_t next_ = 0; ///< the first step not yet taken by actions()
    glm::dvec2 mouse_{0};
    int mods_ = 0;
};

} // namespace sonarsim::ui

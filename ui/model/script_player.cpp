#include "ui/model/script_player.hpp"

#include "core/base/errors.hpp"

#include <algorithm>
#include <utility>

namespace sonarsim::ui {

ScriptPlayer::ScriptPlayer(std::vector<ScriptStep> steps, std::string file,
                           std::optional<glm::dvec2> hold_mouse,
                           std::optional<std::array<glm::dvec2, 2>> drag, int frames)
    : steps_(std::move(steps)), file_(std::move(file)), hold_mouse_(hold_mouse), drag_(drag),
      frames_(frames) {
    if (frames > 0)
        last_frame_ = frames - 1;
    else if (!steps_.empty())
        last_frame_ = steps_.back().frame + 1;
}

std::vector<InputEvent> ScriptPlayer::input(int index, const std::map<std::string, Rect>& widgets) {
    std::vector<InputEvent> out;
    if (hold_mouse_ && index == 0) {
        InputEvent e;
        e.pos = *hold_mouse_;
        out.push_back(e);
    }
    if (drag_ && frames_ >= 4 && index <= frames_ - 1) {
        // Frame 0: hover at the start; 1: press; then move linearly; last frame: release at the end.
        const double t = std::clamp(double(index - 1) / (frames_ - 3), 0.0, 1.0);
        InputEvent e;
        e.pos = (*drag_)[0] + t * ((*drag_)[1] - (*drag_)[0]);
        out.push_back(e);
        e.type = index == 1 ? InputEvent::Type::Press : InputEvent::Type::Release;
        if (index == 1 || index == frames_ - 1) out.push_back(e);
    }
    for (size_t i = next_; i < steps_.size() && steps_[i].frame <= index; ++i) {
        const ScriptStep& st = steps_[i];
        if (st.command == "move_to") {
            const auto it = widgets.find(st.args[0]);
            if (it == widgets.end())
                throw InputError(file_, "line " + std::to_string(st.line),
                                 "move_to " + st.args[0] +
                                     ": that widget is not on screen (scrolled out of the controls panel, "
                                     "in a closed section, or not a parameter of this scene)");
            const Rect& r = it->second;
            mouse_ = {r.x + std::stod(st.args[1]) * r.w, r.y + std::stod(st.args[2]) * r.h};
            InputEvent e;
            e.pos = mouse_;
            e.mods = mods_;
            out.push_back(e);
            continue;
        }
        if (is_input_command(st.command))
            for (const InputEvent& e : step_events(st, mouse_, mods_)) out.push_back(e);
    }
    return out;
}

bool ScriptPlayer::has_action(int index, const std::string& command) const {
    for (size_t i = next_; i < steps_.size() && steps_[i].frame <= index; ++i)
        if (steps_[i].command == command) return true;
    return false;
}

std::vector<ScriptStep> ScriptPlayer::actions(int index) {
    std::vector<ScriptStep> out;
    for (; next_ < steps_.size() && steps_[next_].frame <= index; ++next_)
        if (!is_input_command(steps_[next_].command)) out.push_back(steps_[next_]);
    return out;
}

} // namespace sonarsim::ui

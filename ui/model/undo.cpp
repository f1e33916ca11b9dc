#include "ui/model/undo.hpp"

#include "core/scene/scene_io.hpp"

namespace sonarsim::ui {

bool same_scene(const SceneDesc& a, const SceneDesc& b) {
    return a.source_file == b.source_file && scene_to_json(a) == scene_to_json(b);
}

UndoStack::UndoStack(const SceneDesc& initial, size_t max_steps) : states_{initial}, max_(max_steps) {}

bool UndoStack::record(const SceneDesc& scene) {
    if (same_scene(scene, states_[pos_])) return false;
    states_.resize(pos_ + 1);
    states_.push_back(scene);
    if (states_.size() > max_ + 1) states_.erase(states_.begin());
    pos_ = states_.size() - 1;
    return true;
}

std::optional<SceneDesc> UndoStack::undo() {
    if (pos_ == 0) return std::nullopt;
    return states_[--pos_];
}

std::optional<SceneDesc> UndoStack::redo() {
    if (pos_ + 1 >= states_.size()) return std::nullopt;
    return states_[++pos_];
}

} // namespace sonarsim::ui

// Undo and redo of scene edits: a stack of scene descriptions (a scene is plain data). The viewer records the
// scene whenever an edit is complete (a drag released, a slider let go, a value typed, a file opened), so one
// drag is one step however many frames it took.
#pragma once
#include "core/data/scene.hpp"

#include <cstddef>
#include <optional>
#include <vector>

namespace sonarsim::ui {

/// True when the two scenes would render and save the same (compared through their scene-file form).
bool same_scene(const SceneDesc& a, const SceneDesc& b);

class UndoStack {
  public:
    explicit UndoStack(const SceneDesc& initial, size_t max_steps = 200);
    /// Records `scene` as the newest state if it differs from the current one (dropping any redo states).
    /// Returns true when a step was added.
    bool record(const SceneDesc& scene);
    /// The state before the current one (which becomes current), or nullopt at the bottom.
    std::optional<SceneDesc> undo();
    /// The state after the current one, or nullopt at the top.
    std::optional<SceneDesc> redo();
    const SceneDesc& current() const { return states_[pos_]; }
    size_t undo_steps() const { return pos_; }
    size_t redo_steps() const { return states_.size() - 1 - pos_; }

  private:
    std::vector<SceneDesc> states_;
    size_t pos_ = 0, max_ = 200;
};

} // namespace sonarsim::ui

// How the viewer names what a scene holds, GL-free: the paper's Fig. 9 scene (which gets the "Fig. 9 pose"
// and "Reset to paper values" buttons) and each object's label in the material combo.
#pragma once
#include "core/data/scene.hpp"

#include <string>

namespace sonarsim::ui {

/// The paper's Fig. 9 scene (the built-in scene, assets/scenes/fig9*.json, or an edit of them): a seafloor
/// and one object, a box of the paper's 70 x 120 x 220 mm prism.
bool is_paper_fig9_scene(const SceneDesc& scene);

/// The combo label of object i: "object i: NAME" from the scene's `name`, else the mesh's file name or
/// "box dx x dy x dz m".
std::string object_label(const SceneDesc& scene, size_t i);
/// The tooltip of object i: its full name and what it is made of (mesh path as written, or box size).
std::string object_tooltip(const SceneDesc& scene, size_t i);

} // namespace sonarsim::ui

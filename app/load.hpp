#pragma once
#include "commands.hpp"
#include "core/data/scene.hpp"

namespace sonarsim::app {
/// Loads the scene named by the options (or the built-in one) and applies --set and --pose.
SceneDesc load_scene_from_options(const SceneOptions& o);
} // namespace sonarsim::app

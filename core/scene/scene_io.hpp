// Scene files (JSON): parsing against the parameter table, serialisation, and the built-in default scene.
#pragma once
#include "core/scene/params.hpp"
#include "core/data/scene.hpp"

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace sonarsim {

/// The paper's Fig. 9 scene: 70 x 120 x 220 mm prism standing on the floor at (1.5, 1.5), sonar at pose 1.
SceneDesc default_scene();

/// Values of group keys (is_group_key: sonar.device, sensor.model) that replace the file's, e.g. from
/// `--set`: like the file's own, they apply before its other keys, which therefore still override them.
using GroupOverrides = std::vector<std::pair<std::string, json>>;

/// Parses a scene from JSON text. `file` names the source in errors; mesh paths resolve relative to
/// `base_dir`.
SceneDesc parse_scene(const std::string& text, const std::string& file, const std::string& base_dir,
                      const GroupOverrides& group_overrides = {});

/// Largest scene file load_scene reads (scene files hold parameters; meshes live in their own files).
constexpr std::uintmax_t kMaxSceneFileBytes = 16u << 20;

/// Reads and parses a scene file. Throws InputError naming the file, key path and what is allowed.
SceneDesc load_scene(const std::string& path, const GroupOverrides& group_overrides = {});

/// Every effective parameter as a scene file (round-trips through parse_scene).
json scene_to_json(const SceneDesc& scene);

/// Parses "x,y,z,roll,pitch,yaw" into a pose; throws InputError naming `origin`.
Pose parse_pose_text(const std::string& text, const std::string& origin);

} // namespace sonarsim

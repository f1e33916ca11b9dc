// What a scene changes of its device preset: the keys the preset sets (sonar.device) whose value in the
// scene is another one, because a scene file or `--set` gave it. Computed from the scene alone, so the
// metadata of `render`, `batch` and the Python module list the same keys.
#pragma once
#include "core/data/scene.hpp"

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace sonarsim {

struct DeviceOverride {
    std::string key;       ///< a key the preset sets, e.g. "sonar.beams"
    nlohmann::json preset; ///< the preset's value
    nlohmann::json value;  ///< the scene's value
};

/// The preset's keys whose value in `scene` differs from the preset's; empty without a preset. The preset's
/// effect switches (sensor rows with an ideal value) count only under sensor.model "device", as only then
/// does the preset set them.
std::vector<DeviceOverride> device_overrides(const SceneDesc& scene);

/// [{"key", "preset", "value"}, ...]: the metadata's device_overrides.
nlohmann::json device_overrides_json(const std::vector<DeviceOverride>& overrides);

} // namespace sonarsim

// The group keys: sonar.device applies a device preset's values (the keys whose rows say preset_may_set,
// checked when the preset is loaded, scene/devices.cpp), sonar.kind returns the rows its kind does not use
// to their defaults, sensor.model sets each effect switch to its ideal or device value.
#include "core/scene/params.hpp"

#include "core/scene/devices.hpp"

#include <algorithm>

namespace sonarsim {
namespace {

/// sensor.model: each row with a value for the model takes it: for "device" the preset's where it gives
/// one, else the row's generic device value (null: left as it is).
void apply_sensor_model(SceneDesc& scene) {
    const DevicePreset* preset = find_device(scene.sonar.device);
    const bool device = scene.sensor.model == SensorModel::Device;
    for (auto& p : scene_params()) {
        if (p.ideal_value.is_null() && p.device_value.is_null()) continue;
        if (!p.used_by(scene.sonar.kind)) continue; // keeps its default
        json v = device ? p.device_value : p.ideal_value;
        if (device && preset)
            for (auto& dv : preset->values)
                if (dv.key == p.key) v = dv.value;
        if (!v.is_null()) p.put(scene, validate_value(p, v, preset ? preset->file : "sensor.model", p.key));
    }
}

/// sonar.device: the preset's values (each a row it may set, device_presets() checked); its effect switches
/// (rows with an "ideal" value) only under sensor.model "device".
void apply_device(SceneDesc& scene) {
    const DevicePreset* preset = find_device(scene.sonar.device);
    if (!preset) return;                   // "none": the values stay as they are
    scene.sonar.kind = SonarKind::Imaging; // unless the preset names another kind
    for (auto& dv : preset->values) {
        const ParamSpec& p = *find_param(dv.key);
        if (p.ideal_value.is_null()) p.put(scene, validate_value(p, dv.value, preset->file, dv.key));
    }
    reset_other_kinds_rows(scene); // a preset of another kind leaves none of the last kind's values
    if (scene.sensor.model == SensorModel::Device) apply_sensor_model(scene);
}

} // namespace

const std::vector<std::string>& group_keys() {
    static const std::vector<std::string> keys = {"sonar.device", "sonar.kind", "sensor.model"};
    return keys;
}

bool is_group_key(const std::string& key) {
    return std::find(group_keys().begin(), group_keys().end(), key) != group_keys().end();
}

void apply_group_key(SceneDesc& scene, const std::string& key) {
    if (key == "sonar.device") apply_device(scene);
    if (key == "sonar.kind") reset_other_kinds_rows(scene);
    if (key == "sensor.model") apply_sensor_model(scene);
}

void reset_other_kinds_rows(SceneDesc& scene) {
    static const SceneDesc defaults;
    for (auto& p : scene_params())
        if (!p.used_by(scene.sonar.kind)) p.put(scene, p.get(defaults));
}

std::string kind_name(SonarKind kind) {
    return find_param("sonar.kind")->choices.at(size_t(kind));
}

std::string preset_keys_text() {
    std::string keys;
    for (auto& p : scene_params())
        if (p.preset_may_set) keys += (keys.empty() ? "" : ", ") + p.key;
    return keys;
}

} // namespace sonarsim

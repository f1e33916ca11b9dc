#include "core/scene/device_overrides.hpp"

#include "core/scene/devices.hpp"
#include "core/scene/params.hpp"

namespace sonarsim {

std::vector<DeviceOverride> device_overrides(const SceneDesc& scene) {
    std::vector<DeviceOverride> out;
    const DevicePreset* preset = find_device(scene.sonar.device);
    if (!preset) return out;
    const bool device_sensor = scene.sensor.model == SensorModel::Device;
    for (auto& dv : preset->values) {
        const ParamSpec* p = find_param(dv.key);
        if (!p || (!p->ideal_value.is_null() && !device_sensor)) continue;
        const json want = validate_value(*p, dv.value, preset->file, dv.key);
        const json have = p->get(scene);
        if (have != want) out.push_back({dv.key, want, have});
    }
    return out;
}

nlohmann::json device_overrides_json(const std::vector<DeviceOverride>& overrides) {
    nlohmann::json j = nlohmann::json::array();
    for (auto& o : overrides) j.push_back({{"key", o.key}, {"preset", o.preset}, {"value", o.value}});
    return j;
}

} // namespace sonarsim

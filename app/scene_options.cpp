#include "commands.hpp"

namespace sonarsim::app {

void add_scene_options(CLI::App& cmd, SceneOptions& o) {
    cmd.add_option("--scene", o.scene_file, "Scene file (JSON); default: the built-in Fig. 9 scene");
    cmd.add_option("--pose", o.pose, "Sonar pose x,y,z,roll,pitch,yaw in m and deg (overrides the scene)");
    cmd.add_option("--set", o.sets, "Override a parameter, e.g. --set sonar.range_max_m=8 (repeatable)")
        ->take_all();
}

} // namespace sonarsim::app

#include "core/scene/device_overrides.hpp"
#include "core/scene/params.hpp"
#include "core/scene/scene_io.hpp"
#include "load.hpp"

#include <algorithm>
#include <iostream>

namespace sonarsim::app {
namespace {

/// "sonar.beams 128 (preset 512, from --set), ...": the preset's keys the scene or --set changed.
std::string overrides_text(const std::vector<DeviceOverride>& overrides,
                           const std::vector<std::string>& set_keys, const std::string& scene_file) {
    std::string text;
    for (auto& o : overrides) {
        const bool by_set = std::find(set_keys.begin(), set_keys.end(), o.key) != set_keys.end();
        text += (text.empty() ? "" : ", ") + o.key + " " + o.value.dump() + " (preset " + o.preset.dump() +
                ", from " +
                (by_set               ? std::string("--set")
                 : scene_file.empty() ? "the built-in scene"
                                      : scene_file) +
                ")";
    }
    return text;
}

} // namespace

SceneDesc load_scene_from_options(const SceneOptions& o) {
    // sensor.model applies before the scene file's keys, so that the file's sensor keys still override the
    // model. sonar.device applies after them: a device named on the command line brings every value its
    // preset sets over the file's (the file's other keys stay); so does a material preset
    // (KEY.material.preset, water.surface_material.preset). Every other --set applies last, in order, and
    // overrides them all.
    GroupOverrides model;
    std::vector<std::pair<std::string, json>> device, rest;
    const std::string material_preset = "material." + material_preset_param().key;
    for (auto& s : o.sets) {
        auto kv = parse_setting_text(s, "--set");
        const std::string& k = kv.first;
        const bool preset = k == "sonar.device" || (k.size() >= material_preset.size() &&
                                                    k.compare(k.size() - material_preset.size(),
                                                              material_preset.size(), material_preset) == 0);
        (preset ? device : is_group_key(k) ? model : rest).push_back(std::move(kv));
    }
    SceneDesc scene = default_scene();
    if (o.scene_file.empty())
        for (auto& [k, v] : model) apply_setting(scene, k, v, "--set");
    else
        scene = load_scene(o.scene_file, model); // checked by itself: what fails below, --set or --pose did
    for (auto& [k, v] : device) apply_setting(scene, k, v, "--set");
    std::vector<std::string> set_keys;
    for (auto& [k, v] : rest) apply_setting(scene, k, v, "--set"), set_keys.push_back(k);
    if (!o.pose.empty()) scene.sonar.pose = parse_pose_text(o.pose, "--pose");
    const std::string origin = o.scene_file.empty() || !o.sets.empty() ? "--set"
                               : !o.pose.empty()                       ? "--pose"
                                                                       : o.scene_file;
    validate_scene(scene, origin, set_keys);
    if (const auto overrides = device_overrides(scene); !overrides.empty())
        std::cerr << "sonarsim: note: " << overrides.size() << " value" << (overrides.size() > 1 ? "s" : "")
                  << " of device preset " << scene.sonar.device
                  << " overridden (the metadata lists them as device_overrides): "
                  << overrides_text(overrides, set_keys, o.scene_file) << "\n";
    return scene;
}

} // namespace sonarsim::app

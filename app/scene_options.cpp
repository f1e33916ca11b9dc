#include "commands.hpp"

namespace sonarsim::app {

void add_scene_options(CLI::App& cmd, SceneOptions& o) {
    cmd.add_option("--scene", o.scene_file, "Scene file (JSON); default: the built-in Fig. 9 scene");
    cmd.add_option("--pose", o.pose, "Sonar pose x,y,z,roll,pitch,yaw in m and deg (overrides the scene)");
    cmd.add_option("--set", o.sets, "Override a parameter, e.g. --set sonar.range_max_m=8 (repeatable)")
        ->take_all();
}

} // namespace sonarsim::app

#include "core/scene/params.hpp"
#include "core/scene/scene_io.hpp"
#include "load.hpp"

namespace sonarsim::app {

SceneDesc load_scene_from_options(const SceneOptions& o) {
    // Group keys (sonar.device, sensor.model) apply before the scene file's other keys, so that those
    // still override the preset; every other --set applies after the file, in order.
    GroupOverrides groups;
    std::vector<std::pair<std::string, json>> rest;
    for (auto& s : o.sets) {
        auto kv = parse_setting_text(s, "--set");
        (is_group_key(kv.first) ? groups : rest).push_back(std::move(kv));
    }
    SceneDesc scene = default_scene();
    if (o.scene_file.empty())
        for (auto& [k, v] : groups) apply_setting(scene, k, v, "--set");
    else
        scene = load_scene(o.scene_file, groups);
    for (auto& [k, v] : rest) apply_setting(scene, k, v, "--set");
    if (!o.pose.empty()) scene.sonar.pose = parse_pose_text(o.pose, "--pose");
    validate_scene(scene, o.scene_file.empty() ? "--set" : o.scene_file);
    return scene;
}

} // namespace sonarsim::app

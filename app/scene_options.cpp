#include "commands.hpp"

namespace sonarsim::app {

void add_scene_options(CLI::App& cmd, SceneOptions& o) {
    cmd.add_option("--scene", o.scene_file, "Scene file (JSON); default: the built-in Fig. 9 scene");
    cmd.add_option("--pose", o.pose, "Sonar pose x,y,z,roll,pitch,yaw in m and deg (overrides the scene)");
    cmd.add_option("--set", o.sets, "Override a parameter, e.g. --set sonar.range_max_m=8 (repeatable)")
        ->take_all();
}

} // namespace sonarsim::app

#include "core/params.hpp"
#include "core/scene_io.hpp"
#include "load.hpp"

namespace sonarsim::app {

SceneDesc load_scene_from_options(const SceneOptions& o) {
    SceneDesc scene = o.scene_file.empty() ? default_scene() : load_scene(o.scene_file);
    for (auto& s : o.sets) apply_setting_text(scene, s, "--set");
    if (!o.pose.empty()) scene.sonar.pose = parse_pose_text(o.pose, "--pose");
    validate_scene(scene, o.scene_file.empty() ? "--set" : o.scene_file);
    return scene;
}

} // namespace sonarsim::app

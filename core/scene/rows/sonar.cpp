// The sonar's rows of the parameter table: the device preset, the pose, the fan (fields of view, beams,
// range window and bins) and the levels (source, noise).
#include "core/scene/param_rows.hpp"

#include "core/grid/beam_tables.hpp"
#include "core/scene/devices.hpp"

namespace sonarsim::rows {

std::vector<ParamSpec> sonar_rows() {
    std::vector<ParamSpec> t;
    ParamSpec device = blank<ParamSpec>("sonar.device", "", ParamType::Enum,
                                        Stage::None, // what it changes is compared key by key
                                        "Device preset (assets/devices/NAME.json, `sonarsim devices`): sets "
                                        "the device's values; keys given in "
                                        "the scene override them");
    device.choices = device_choices();
    device.get = [](const SceneDesc& s) { return json(s.sonar.device); };
    device.put = [](SceneDesc& s, const json& v) { s.sonar.device = v.get<std::string>(); };
    t.push_back(device);
    t.push_back(vec3("sonar.position", "m", -1e6, 1e6, Stage::Trace, "Sonar position x, y, z (world, z up)",
                     [](S s) -> Vec3d& { return s.sonar.pose.position_m; })
                    .in_section(Section::Pose)
                    .with_label("position x y z"));
    t.push_back(vec3("sonar.orientation_deg", "deg", -360, 360, Stage::Trace,
                     "Roll, pitch, yaw; R = Rz(yaw) Ry(pitch) Rx(roll); positive pitch looks down",
                     [](S s) -> Vec3d& { return s.sonar.pose.orientation_deg; })
                    .in_section(Section::Pose)
                    .with_label("roll pitch yaw"));
    t.push_back(number("sonar.frequency_khz", "kHz", 1, 10000, false, false, Stage::Shade,
                       "Carrier frequency f (absorption, eq. 7)",
                       [](S s) -> double& { return s.sonar.frequency_khz; })
                    .steers()
                    .preset()
                    .with_label("f frequency")
                    .with_log_slider(100, 5000));
    t.push_back(number("sonar.azimuth_fov_deg", "deg", 0, 180, true, true, Stage::Trace,
                       "Azimuth field of view Theta (side-scan, scanning: the beam's horizontal width)",
                       [](S s) -> double& { return s.sonar.azimuth_fov_deg; })
                    .preset()
                    .with_label("azimuth FOV")
                    .with_slider(2, 130));
    t.push_back(
        number(
            "sonar.elevation_fov_deg", "deg", 0, 180, true, true, Stage::Trace,
            "Elevation aperture Phi (side-scan: the beam's width across track; scanning: its vertical width)",
            [](S s) -> double& { return s.sonar.elevation_fov_deg; })
            .preset()
            .with_label("elevation FOV")
            .with_slider(1, 60));
    t.push_back(integer("sonar.beams", 1, 4096, Stage::Trace, "Number of beams N (eq. 10)",
                        [](S s) -> int& { return s.sonar.beams; })
                    .preset()
                    .only_for({SonarKind::Imaging})
                    .with_log_slider(8, 512));
    ParamSpec table =
        blank<ParamSpec>("sonar.beam_table", "", ParamType::Enum, Stage::Trace,
                         "Beam angles: uniform (eq. 10), or a device's per-beam centres and edges "
                         "(assets/devices/beam_tables/NAME.csv, its beam count; the fan spans "
                         "its edges)");
    table.choices = {kUniformBeams};
    for (const std::string& n : beam_table_names()) table.choices.push_back(n);
    table.get = [](const SceneDesc& s) { return json(s.sonar.beam_table); };
    table.put = [](SceneDesc& s, const json& v) { s.sonar.beam_table = v.get<std::string>(); };
    t.push_back(table.preset().only_for({SonarKind::Imaging}).with_label("beam table"));
    t.push_back(number("sonar.range_min_m", "m", 0, 1000, false, true, Stage::Trace,
                       "Start of the range window r_min", [](S s) -> double& { return s.sonar.range_min_m; })
                    .preset()
                    .with_slider(0, 10));
    t.push_back(number("sonar.range_max_m", "m", 0, 1000, true, false, Stage::Trace,
                       "End of the range window r_max", [](S s) -> double& { return s.sonar.range_max_m; })
                    .preset()
                    .with_log_slider(0.5, 40));
    t.push_back(integer("sonar.range_bins", 1, 65536, Stage::Trace, "Range bins K over [r_min, r_max)",
                        [](S s) -> int& { return s.sonar.range_bins; })
                    .preset()
                    .with_log_slider(32, 2048));
    t.push_back(number("sonar.source_level_db", "dB", 0, 300, false, false, Stage::Shade,
                       "Source level L_S (dB re 1 uPa at 1 m)",
                       [](S s) -> double& { return s.sonar.source_level_db; })
                    .preset()
                    .with_label("L_S source level")
                    .with_slider(150, 250));
    t.push_back(number("sonar.noise_level_db", "dB", -200, 300, false, false, Stage::Shade, "Noise level L_N",
                       [](S s) -> double& { return s.sonar.noise_level_db; })
                    .preset()
                    .with_label("L_N noise level")
                    .with_slider(-40, 100));
    return t;
}

std::vector<ParamSpec> motion_rows() {
    std::vector<ParamSpec> t;
    t.push_back(vec3("sonar.velocity_mps", "m/s", -100, 100, Stage::Trace,
                     "Motion during a frame: velocity in the sonar's frame (x forward, y port, z up) at the "
                     "frame's first transmit; each echo is traced from the pose of its receive time",
                     [](S s) -> Vec3d& { return s.sonar.velocity_mps; })
                    .in_section(Section::Motion)
                    .with_label("velocity x y z"));
    t.push_back(vec3("sonar.angular_rate_dps", "deg/s", -1000, 1000, Stage::Trace,
                     "Motion during a frame: rates about the sonar's x, y, z axes (roll, pitch, yaw rate; "
                     "positive yaw turns to port)",
                     [](S s) -> Vec3d& { return s.sonar.angular_rate_dps; })
                    .in_section(Section::Motion)
                    .with_label("turn rate roll pitch yaw"));
    t.push_back(integer("sonar.pings_per_frame", 1, 64, Stage::Trace,
                        "Pings that build one frame: ping k fires every P-th beam (ARIS: beams / 16); pings "
                        "follow each other every 2 r_max / c + 0.42 ms. Matters only with motion",
                        [](S s) -> int& { return s.sonar.pings_per_frame; })
                    .preset()
                    .only_for({SonarKind::Imaging})
                    .in_section(Section::Motion)
                    .with_label("pings per frame")
                    .with_slider(1, 16));
    // batch only: not in the viewer.
    t.push_back(boolean("sonar.motion_from_trajectory", Stage::None,
                        "batch: each frame's sonar.velocity_mps and sonar.angular_rate_dps from its "
                        "trajectory (the difference of its neighbouring poses over their times)",
                        [](S s) -> bool& { return s.sonar.motion_from_trajectory; }));
    return t;
}

} // namespace sonarsim::rows

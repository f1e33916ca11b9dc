// The kind of sonar (sonar.kind) and the rows of the kinds other than the imaging fan: a side-scan's tilt,
// pings and waterfall, a scanning head's sector and steps. Each of those is used by its kind only.
#include "core/scene/param_rows.hpp"

namespace sonarsim::rows {

std::vector<ParamSpec> kind_rows() {
    std::vector<ParamSpec> t;
    auto sidescan = [&](ParamSpec p) { t.push_back(p.only_for({SonarKind::Sidescan})); };
    auto scanning = [&](ParamSpec p) { t.push_back(p.only_for({SonarKind::Scanning})); };
    t.push_back(
        enumeration<SonarKind>(
            "sonar.kind", {"imaging", "sidescan", "scanning"}, Stage::Trace,
            "imaging: a forward-looking fan of beams (one image a frame); sidescan: two beams, port and "
            "starboard, tilted down, whose pings form a waterfall; scanning: one beam stepped by a "
            "turning head, one ping a step, a sweep an image. Keys another kind uses are rejected",
            [](S s) -> SonarKind& { return s.sonar.kind; })
            .preset()
            .with_label("kind")
            .in_section(Section::Sonar));
    sidescan(number("sidescan.depression_deg", "deg", 0, 90, false, false, Stage::Trace,
                    "Each transducer's axis below the horizontal (port and starboard alike)",
                    [](S s) -> double& { return s.sidescan.depression_deg; })
                 .preset()
                 .with_label("depression")
                 .with_slider(0, 60)
                 .in_section(Section::Sonar));
    sidescan(integer("sidescan.pings", 1, 100000, Stage::Trace,
                     "Pings of one waterfall (its rows, newest at the top); each traced from the pose at its "
                     "time (sonar.velocity_mps, sonar.angular_rate_dps)",
                     [](S s) -> int& { return s.sidescan.pings; })
                 .with_log_slider(10, 2000)
                 .in_section(Section::Sonar));
    sidescan(enumeration<SidescanRange>(
                 "sidescan.range", {"slant", "ground"}, Stage::Display,
                 "The waterfall's columns: slant range as recorded (the water column before the first "
                 "bottom return shows the altitude), or ground range sqrt(r^2 - h^2) over a flat bottom at "
                 "the altitude h of each ping's first bottom return",
                 [](S s) -> SidescanRange& { return s.sidescan.range; })
                 .with_label("range")
                 .in_section(Section::Sonar));
    sidescan(number("sidescan.ping_overhead_ms", "ms", 0, 10000, false, false, Stage::Trace,
                    "Time between pings beyond the listening window 2 r_max / c",
                    [](S s) -> double& { return s.sidescan.ping_overhead_ms; })
                 .preset());
    sidescan(number("sidescan.bottom_threshold_db", "dB", -100, 200, false, false, Stage::Display,
                    "The first bottom return (the ground-range correction's altitude): the first bin whose "
                    "echo over the noise, L_EN, reaches this level",
                    [](S s) -> double& { return s.sidescan.bottom_threshold_db; }));
    scanning(number("scanning.sector_start_deg", "deg", -360, 360, false, false, Stage::Trace,
                    "Head angle of the sweep's first step, from the sonar's forward axis toward port",
                    [](S s) -> double& { return s.scanning.sector_start_deg; })
                 .with_label("sector start")
                 .with_slider(-180, 180)
                 .in_section(Section::Sonar));
    scanning(number("scanning.sector_end_deg", "deg", -360, 360, false, false, Stage::Trace,
                    "Head angle at which the sweep ends (start + 360: a full circle)",
                    [](S s) -> double& { return s.scanning.sector_end_deg; })
                 .with_label("sector end")
                 .with_slider(-180, 180)
                 .in_section(Section::Sonar));
    scanning(number("scanning.step_deg", "deg", 0, 90, true, false, Stage::Trace,
                    "Head angle between pings (Ping360: 1 gradian = 0.9 deg, 1-10 motor steps)",
                    [](S s) -> double& { return s.scanning.step_deg; })
                 .preset()
                 .with_label("step")
                 .with_slider(0.45, 9)
                 .in_section(Section::Sonar));
    scanning(number("scanning.step_overhead_ms", "ms", 0, 10000, false, false, Stage::Trace,
                    "Time of a step beyond the listening window 2 r_max / c (motor and link)",
                    [](S s) -> double& { return s.scanning.step_overhead_ms; })
                 .preset());
    return t;
}

} // namespace sonarsim::rows

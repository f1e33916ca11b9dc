// Side-scan and scanning sonars against closed forms: the nadir gap, ground range, the level against the
// flat-floor integral, a cube's shadow, independent channels, a round tank's wall from a still and a moving
// head, and the ping timing.
#include "core/analysis/reference.hpp"
#include "core/base/errors.hpp"
#include "core/display/display_range.hpp"
#include "core/scene/devices.hpp"
#include "core/io/ping360_log.hpp"
#include "core/io/ping_output.hpp"
#include "core/io/ping360_log_read.hpp"
#include "core/io/xtf.hpp"
#include "core/io/xtf_read.hpp"
#include "core/kinds/kind_images.hpp"
#include "core/kinds/ping_series.hpp"
#include "core/scene/params.hpp"
#include "core/scene/scene_io.hpp"
#include "core/shading/physics.hpp"
#include "support.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <sstream>

using namespace sonarsim;
using sonarsim::test::out_path;

namespace {

/// A side-scan at altitude `h_m` over a bare flat floor, heading +x, pinging `pings` times while still.
SceneDesc sidescan_scene(double h_m, int pings = 4) {
    SceneDesc s;
    apply_setting(s, "sonar.kind", "sidescan", "test");
    s.sonar.pose = {{0, 0, h_m}, {0, 0, 0}};
    s.sonar.frequency_khz = 400;
    s.sonar.azimuth_fov_deg = 1.0;
    s.sonar.elevation_fov_deg = 100; // from 5 deg above the horizon to 5 deg past nadir
    s.sidescan.depression_deg = 45;
    s.sonar.range_min_m = 0.5, s.sonar.range_max_m = 20, s.sonar.range_bins = 400;
    s.sonar.source_level_db = 210, s.sonar.noise_level_db = 40;
    s.sidescan.pings = pings;
    s.seafloor = Seafloor{};
    s.seafloor->material.nu_db = -30;
    validate_scene(s, "test");
    return s;
}

ObjectDesc box(Vec3d size_m, Vec3d centre_m, double nu_db) {
    ObjectDesc o;
    o.box_m = size_m, o.position_m = centre_m;
    o.material.nu_db = nu_db;
    return o;
}

/// Near edge of the first bin of `profile` at or beyond bin `from` whose level reaches `threshold_db`
/// (-1: none).
int first_bin_at_least(const float* profile, int bins, double threshold_db, int from = 0) {
    for (int k = from; k < bins; ++k)
        if (profile[k] >= threshold_db) return k;
    return -1;
}

/// A vertical cylinder wall of radius r_m from z = 0 to 2 m, 720 faces, as an OBJ file.
std::string tank_obj(double r_m) {
    const std::string path =
        out_path("kinds_tank_" + std::to_string(int(std::lround(r_m * 1000))) + "mm.obj");
    std::ostringstream f;
    const int n = 720;
    for (int i = 0; i < n; ++i) {
        const double a = 2 * 3.14159265358979323846 * i / n;
        f << "v " << r_m * std::cos(a) << " " << r_m * std::sin(a) << " 0\n";
        f << "v " << r_m * std::cos(a) << " " << r_m * std::sin(a) << " 2\n";
    }
    for (int i = 0; i < n; ++i) {
        const int a = 2 * i + 1, b = 2 * i + 2, c = 2 * ((i + 1) % n) + 1, d = 2 * ((i + 1) % n) + 2;
        f << "f " << a << " " << c << " " << d << "\nf " << a << " " << d << " " << b << "\n";
    }
    sonarsim::test::write_text_atomically(path, f.str());
    return path;
}

/// A scanning sonar at (x, 0, 1) in a round tank of radius r_m (no floor), full circle in 3.6 deg steps.
SceneDesc tank_scan(double r_m) {
    SceneDesc s;
    apply_setting(s, "sonar.kind", "scanning", "test");
    s.sonar.pose = {{0, 0, 1}, {0, 0, 0}};
    s.sonar.frequency_khz = 750;
    s.sonar.azimuth_fov_deg = 2, s.sonar.elevation_fov_deg = 25;
    s.sonar.range_min_m = 0.3, s.sonar.range_max_m = 8, s.sonar.range_bins = 400;
    s.sonar.source_level_db = 200, s.sonar.noise_level_db = 40;
    s.scanning.step_deg = 3.6;
    s.seafloor.reset();
    ObjectDesc wall;
    wall.mesh = wall.mesh_resolved = tank_obj(r_m);
    wall.material.nu_db = -20;
    s.objects = {wall};
    validate_scene(s, "test");
    return s;
}

} // namespace

TEST_CASE("side-scan over a flat floor: nothing before the altitude, the first return at it, each channel's "
          "level within 0.2 dB median of the flat-floor integral",
          "[kinds]") {
    const double h = 6;
    const SceneDesc s = sidescan_scene(h);
    const PingSeries p = render_pings(s);
    REQUIRE(p.pings == 4);
    REQUIRE(p.channels == 2);
    const double bin = p.grid->bin_m;
    for (int ping = 0; ping < p.pings; ++ping) {
        CHECK(std::abs(p.first_return_m[size_t(ping)] - h) <= bin);
        for (int ch = 0; ch < 2; ++ch) {
            const float* ideal = p.ideal_db.data() + (size_t(ping) * 2 + size_t(ch)) * size_t(p.bins);
            for (int k = 0; k < p.bins; ++k)
                if (p.grid->bin_near_edge_m(k) + bin < h) CHECK_FALSE(std::isfinite(ideal[k]));
        }
    }
    // Each channel is a one-beam imaging sonar at its transducer's pose: the integral of a bare floor.
    for (int ch = 0; ch < 2; ++ch) {
        SceneDesc beam = beam_scene(s);
        beam.sonar.pose = transducer_pose(s, p.schedule[0], ch);
        const PolarImage ref = floor_reference(beam);
        PolarImage got;
        got.bins = p.bins, got.beams = 1;
        got.level_db.assign(p.ideal_db.begin() + ptrdiff_t(ch) * p.bins,
                            p.ideal_db.begin() + ptrdiff_t(ch + 1) * p.bins);
        const ImageError e = compare_images(got, ref);
        INFO("channel " << ch << ": median " << e.median_abs_db << " dB, rel L1 " << e.rel_l1);
        CHECK(e.median_abs_db < 0.2);
        CHECK(e.echoing_ref > p.bins / 2);
    }
}

TEST_CASE(
    "side-scan ground truth per sample over a flat floor: each echo on the floor at its bin's range, on "
    "its side, at incidence acos(h / r)",
    "[kinds]") {
    const double h = 6;
    const SceneDesc s = sidescan_scene(h, 2);
    PingControl control;
    control.ground_truth = true;
    const PingSeries p = render_pings(s, control);
    REQUIRE(p.truth.size() == size_t(p.pings) * 2);
    const double bin = p.grid->bin_m;
    int checked = 0;
    for (int ping = 0; ping < p.pings; ++ping)
        for (int ch = 0; ch < 2; ++ch) {
            const GroundTruth& g = p.truth[size_t(ping) * 2 + size_t(ch)];
            REQUIRE(g.bins == p.bins);
            REQUIRE(g.beams == 1);
            const Vec3d x = transducer_pose(s, p.schedule[size_t(ping)], ch).position_m;
            for (int k = 0; k < p.bins; ++k) {
                const double r = p.grid->bin_near_edge_m(k) + bin / 2; // the bin's centre range
                if (g.object_id[size_t(k)] != 0 || r < h + 2 * bin) continue;
                const float* pt = g.point_m.data() + 3 * size_t(k);
                const double dx = pt[0] - x[0], dy = pt[1] - x[1], dz = pt[2] - x[2];
                INFO("ping " << ping << ", channel " << ch << ", bin " << k);
                CHECK(std::abs(pt[2]) < bin / 10); // on the floor (z = 0)
                CHECK(std::abs(std::sqrt(dx * dx + dy * dy + dz * dz) - r) <= bin / 2); // at the bin's range
                CHECK((ch == 0 ? dy > 0 : dy < 0));                                     // port is +y
                CHECK(g.incidence_deg[size_t(k)] == Approx(std::acos(h / r) * 180 / kPi).margin(1.0));
                ++checked;
            }
        }
    CHECK(checked > p.pings * 2 * p.bins / 2);
}

TEST_CASE("a side-scan that does not move: every ping the same echo, each its own noise, the same bytes "
          "every run",
          "[kinds]") {
    SceneDesc s = sidescan_scene(6, 3);
    apply_setting(s, "sensor.model", "device", "test");
    apply_setting(s, "sensor.noise", true, "test");
    validate_scene(s, "test");
    const PingSeries p = render_pings(s);
    const size_t n = size_t(p.channels) * size_t(p.bins);
    for (int ping = 1; ping < p.pings; ++ping) {
        CHECK(std::equal(p.ideal_db.begin(), p.ideal_db.begin() + long(n),
                         p.ideal_db.begin() + long(ping * n)));
        size_t differ = 0;
        for (size_t i = 0; i < n; ++i) differ += p.level_db[i] != p.level_db[size_t(ping) * n + i];
        CHECK(differ > n / 2); // the noise is drawn anew
    }
    CHECK(render_pings(s).level_db == p.level_db);
}

TEST_CASE("side-scan ground range: a bright strip on the floor at ground range 8-10 m shows there, within "
          "one bin, in both channels' halves",
          "[kinds]") {
    const double h = 5;
    SceneDesc s = sidescan_scene(h, 2);
    // Strips 2 cm thick along the track, to starboard (y < 0) and port (y > 0), 2 m wide.
    s.objects = {box({40, 2, 0.02}, {0, -9, 0.01}, -5), box({40, 2, 0.02}, {0, 9, 0.01}, -5)};
    s.sidescan.range = SidescanRange::Ground;
    const PingSeries p = render_pings(s);
    const PolarImage w = waterfall_levels(p, SidescanRange::Ground, s.sonar.range_max_m);
    SceneDesc bare = s;
    bare.objects.clear();
    const PolarImage floor = waterfall_levels(render_pings(bare), SidescanRange::Ground, s.sonar.range_max_m);
    const double ground_bin = s.sonar.range_max_m / p.bins;
    // The strip is 25 dB above the floor: its columns are those 10 dB above the bare floor's.
    for (int side = 0; side < 2; ++side) {
        double first = -1, last = -1;
        for (int j = 0; j < p.bins; ++j) {
            const int col = side == 0 ? p.bins - 1 - j : p.bins + j;
            if (std::isfinite(w.at(0, col)) && w.at(0, col) >= floor.at(0, col) + 10) {
                if (first < 0) first = j * ground_bin;
                last = (j + 1) * ground_bin;
            }
        }
        INFO("side " << side << ": strip from " << first << " to " << last << " m");
        CHECK(std::abs(first - 8) <= ground_bin);
        CHECK(std::abs(last - 10) <= ground_bin);
    }
    // Slant range: the strip spans sqrt(g^2 + h^2).
    const PolarImage slant = waterfall_levels(p, SidescanRange::Slant, s.sonar.range_max_m);
    const int k8 = p.grid->bin_of(std::hypot(8.0, h)), k10 = p.grid->bin_of(std::hypot(10.0, h));
    CHECK(slant.at(0, p.bins + k8 + 2) > slant.at(0, p.bins + k8 - 3) + 15);
    CHECK(slant.at(0, p.bins + k10 - 3) > slant.at(0, p.bins + k10 + 2) + 15);
}

TEST_CASE("side-scan: a 1 m cube's shadow ends at ground range x h / (h - 1), and only its side sees it",
          "[kinds]") {
    const double h = 4, x_far = 9;
    SceneDesc s = sidescan_scene(h, 1);
    s.sonar.range_bins = 800;
    s.sonar.source_level_db = 220;
    s.objects = {box({1, 1, 1}, {0, -(x_far - 0.5), 0.5}, -20)}; // to starboard, far top edge at 9 m
    const PingSeries p = render_pings(s);
    const PolarImage w = waterfall_levels(p, SidescanRange::Ground, s.sonar.range_max_m);
    const double ground_bin = s.sonar.range_max_m / p.bins;
    // Starboard columns beyond the cube: the first that echoes again ends the shadow.
    const int from = int(x_far / ground_bin) + 1;
    int end = -1;
    for (int j = from; j < p.bins && end < 0; ++j)
        if (std::isfinite(w.at(0, p.bins + j))) end = j;
    REQUIRE(end > 0);
    const double shadow_end = end * ground_bin, expected = x_far * h / (h - 1);
    INFO("shadow ends at " << shadow_end << " m, expected " << expected);
    CHECK(std::abs(shadow_end - expected) <= 2 * ground_bin);
    // Port sees a bare floor: the same profile as without the cube.
    SceneDesc bare = s;
    bare.objects.clear();
    const PingSeries q = render_pings(bare);
    for (int k = 0; k < p.bins; ++k) CHECK(p.profile(0, 0)[k] == q.profile(0, 0)[k]);
    int differ = 0;
    for (int k = 0; k < p.bins; ++k) differ += p.profile(0, 1)[k] != q.profile(0, 1)[k];
    CHECK(differ > 50);
}

TEST_CASE("scanning sonar at the centre of a round tank: the wall at R in every step, within one bin",
          "[kinds]") {
    const double R = 5;
    const SceneDesc s = tank_scan(R);
    const PingSeries p = render_pings(s);
    REQUIRE(p.pings == 100);
    REQUIRE(p.channels == 1);
    for (int i = 0; i < p.pings; ++i) {
        const int k = first_bin_at_least(p.profile(i, 0), p.bins, 10);
        INFO("step " << i << " head " << p.schedule[size_t(i)].head_deg);
        REQUIRE(k >= 0);
        CHECK(std::abs(k - p.grid->bin_of(R)) <= 1);
    }
}

TEST_CASE("scanning sonar moving at v during its sweep: the step fired at t sees the wall from x0 + v t, "
          "within one bin",
          "[kinds]") {
    const double R = 5, v = 0.6;
    SceneDesc s = tank_scan(R);
    s.sonar.velocity_mps = {v, 0, 0};
    // A narrow beam: off the centre the wall is met obliquely, and a 2 deg beam's edge would find it a bin
    // or two nearer than its axis does.
    s.sonar.azimuth_fov_deg = 0.2;
    const PingSeries p = render_pings(s);
    const double sweep_s = p.schedule.back().time_s;
    REQUIRE(v * sweep_s > 2); // the sonar crosses two metres of the tank in one sweep: a visible distortion
    for (int i = 0; i < p.pings; ++i) {
        const Ping& g = p.schedule[size_t(i)];
        const double d = v * g.time_s, a = g.head_deg * 3.14159265358979323846 / 180;
        CHECK(g.vehicle.position_m[0] == Approx(d));
        // From (d, 0) along (cos a, sin a) to the circle of radius R.
        const double wall = -d * std::cos(a) + std::sqrt(R * R - d * d * std::sin(a) * std::sin(a));
        const int k = first_bin_at_least(p.profile(i, 0), p.bins, 10);
        INFO("step " << i << " at " << g.time_s << " s, head " << g.head_deg << " deg: wall at " << wall);
        REQUIRE(k >= 0);
        CHECK(std::abs(k - p.grid->bin_of(wall)) <= 1);
    }
}

TEST_CASE(
    "ping timing: 2 r_max / c plus the kind's overhead, and a full circle of 0.9 deg steps is 400 pings",
    "[kinds]") {
    SceneDesc s = sidescan_scene(5, 3);
    s.sidescan.ping_overhead_ms = 2;
    const double c = sound_speed_m_s(s.water.temperature_c, s.water.depth_m);
    const auto pings = ping_schedule(s);
    REQUIRE(pings.size() == 3);
    CHECK(pings[2].time_s == Approx(2 * (2 * 20 / c + 0.002)));
    SceneDesc t = tank_scan(5);
    t.scanning.step_deg = 0.9;
    const auto steps = ping_schedule(t);
    REQUIRE(steps.size() == 400);
    CHECK(steps[1].time_s == Approx(2 * 8 / c + 0.025));
    CHECK(steps[399].head_deg == Approx(-180 + 399 * 0.9));
    t.scanning.sector_start_deg = -45, t.scanning.sector_end_deg = 45;
    const auto sector = sweep_head_angles_deg(t.scanning);
    REQUIRE(sector.size() == 101); // both ends
    CHECK(sector.back() == Approx(45));
}

TEST_CASE("a key another kind uses is an error naming it, and choosing a kind resets the other kinds' keys",
          "[kinds]") {
    SceneDesc s = default_scene();
    s.sonar.beams = 64;
    apply_setting(s, "sonar.kind", "sidescan", "test");
    CHECK(s.sonar.beams == SceneDesc{}.sonar.beams);
    s.sonar.beams = 64;
    try {
        validate_scene(s, "f.json");
        FAIL("no error");
    } catch (const InputError& e) {
        CHECK(std::string(e.what()) == "f.json: sonar.beams: not used by sonar.kind \"sidescan\"; allowed: "
                                       "leave it out, or sonar.kind imaging");
    }
    CHECK_THROWS_AS(
        parse_scene(R"({"sonar": {"kind": "scanning"}, "sidescan": {"pings": 5}})", "g.json", "."),
        InputError);
    const SceneDesc ok =
        parse_scene(R"({"sonar": {"kind": "scanning"}, "scanning": {"step_deg": 1.8}})", "g.json", ".");
    CHECK(ok.scanning.step_deg == 1.8);
    // A scene file written for a kind holds only its keys, and reads back.
    const json j = scene_to_json(ok);
    CHECK_FALSE(j["sonar"].contains("beams"));
    CHECK_FALSE(j.contains("sidescan"));
    CHECK(scene_to_json(parse_scene(j.dump(), "h.json", ".")) == j);
}

TEST_CASE("each side-scan and scanning preset images a floor, most of it neither black nor white",
          "[kinds][devices]") {
    for (auto& preset : device_presets()) {
        if (preset.kind() == "imaging") continue;
        INFO(preset.name);
        SceneDesc s;
        apply_setting(s, "sonar.device", preset.name, "test");
        apply_setting(s, "sensor.model", "device", "test");
        // Level, 5 m over the floor: a side-scan looks down to both sides, a scanning head (pitched 20 deg
        // down) sweeps the floor around it.
        const bool side = s.sonar.kind == SonarKind::Sidescan;
        s.sonar.pose = {{0, 0, 5}, {0, side ? 0.0 : 20.0, 0}};
        if (side)
            s.sidescan.pings = 8;
        else
            s.scanning.step_deg = 9;
        s.objects = {box({2, 2, 2}, {0, -10, 1}, -20)};
        validate_scene(s, "test");
        const PingSeries p = render_pings(s);
        const PolarImage shown =
            side ? waterfall_levels(p, SidescanRange::Slant, s.sonar.range_max_m) : scan_levels(p);
        const DisplayParams d = effective_display(shown, s.display);
        // The cells whose echo stands above the noise (the water column before the first return does not).
        size_t echoing = 0, mid = 0;
        for (size_t i = 0; i < p.level_db.size(); ++i) {
            if (!(p.ideal_db[i] >= 0)) continue;
            ++echoing;
            const float g = gray_level(p.level_db[i], d.lo_db, d.hi_db);
            mid += g > 0 && g < 255;
        }
        CHECK(echoing > p.level_db.size() / 4);
        CHECK(mid > echoing * 8 / 10);
    }
}

TEST_CASE("a side-scan's XTF file read back field by field by the reader written from the layout",
          "[kinds][xtf]") {
    SceneDesc s = sidescan_scene(6, 5);
    s.sonar.velocity_mps = {1.5, 0, 0};
    s.sonar.pose.orientation_deg = {0, 0, 30}; // heading 60 deg clockwise from north
    s.exports.start_time_s = 1767225600.25;    // 2026-01-01 00:00:00.25 UTC
    s.objects = {box({1, 1, 1}, {3, -8, 0.5}, -15)};
    const PingSeries p = render_pings(s);
    const ByteMapping m = ping_byte_mapping(s, p);
    const Bytes bytes = encode_xtf(s, p, m);
    const XtfFile f = read_xtf(bytes, "test.xtf");
    CHECK(f.recording_program == "sonarsim");
    CHECK(f.nav_units == 0);
    REQUIRE(f.sonar_channels == 2);
    CHECK(f.channel_info[0].type == 1);
    CHECK(f.channel_info[1].type == 2);
    CHECK(f.channel_info[0].frequency_khz == Approx(400));
    CHECK(f.channel_info[1].tilt_deg == Approx(45));
    CHECK(f.channel_info[0].horizontal_beam_deg == Approx(1));
    CHECK(f.channel_info[0].bytes_per_sample == 1);
    REQUIRE(f.pings.size() == 5);
    const double c = sound_speed_m_s(s.water.temperature_c, s.water.depth_m);
    for (int i = 0; i < 5; ++i) {
        const XtfPing& x = f.pings[size_t(i)];
        const Ping& g = p.schedule[size_t(i)];
        INFO("ping " << i);
        CHECK(x.ping_number == std::uint32_t(i));
        CHECK(x.year == 2026);
        CHECK(x.month == 1);
        CHECK(x.julian_day == 1);
        const double t = 0.25 + g.time_s;
        CHECK(x.second * 100 + x.hundredths == int(std::floor(t * 100)));
        CHECK(x.sensor_x == Approx(g.vehicle.position_m[0]));
        CHECK(x.sensor_y == Approx(g.vehicle.position_m[1]));
        CHECK(x.heading_deg == Approx(60));
        CHECK(x.altitude_m == Approx(p.first_return_m[size_t(i)]));
        CHECK(x.computed_sound_velocity == Approx(c));
        REQUIRE(x.channels.size() == 2);
        for (int ch = 0; ch < 2; ++ch) {
            const XtfChannelPing& xc = x.channels[size_t(ch)];
            CHECK(xc.channel == ch);
            CHECK(xc.slant_range_m == Approx(20));
            CHECK(xc.time_delay_s == Approx(2 * 0.5 / c));
            CHECK(xc.time_duration_s == Approx(2 * 19.5 / c));
            CHECK(xc.seconds_per_ping == Approx(p.ping_interval_s));
            REQUIRE(xc.samples == std::uint32_t(p.bins));
            // Each sample the byte of its level: back to the level within half a byte's step. Port stored far
            // first, starboard near first (the specification's 2.3.1); near_first in range order for both.
            const double step_db = (m.hi_db - m.lo_db) / 255;
            const auto holds = [&](int byte, float level) {
                if (!std::isfinite(level) || level <= m.lo_db) return byte == 0;
                if (level >= m.hi_db) return byte == 255;
                return std::abs(m.lo_db + byte * step_db - level) <= 0.5 * step_db + 1e-4;
            };
            int stored = 0, ordered = 0;
            for (int k = 0; k < p.bins; ++k) {
                const float* profile = p.profile(i, ch);
                stored += holds(xc.data[size_t(k)], profile[ch == 0 ? p.bins - 1 - k : k]);
                ordered += holds(xc.near_first[size_t(k)], profile[k]);
            }
            CHECK(stored == p.bins);
            CHECK(ordered == p.bins);
        }
    }
    // Malformed: a truncated record names its field.
    Bytes cut(bytes.begin(), bytes.end() - 10);
    CHECK_THROWS_WITH(read_xtf(cut, "cut.xtf"),
                      Catch::Contains("cut.xtf") && Catch::Contains("NumBytesThisRecord"));
}

TEST_CASE("a scan's Ping Viewer log read back field by field by the reader written from the log structure",
          "[kinds][ping360]") {
    SceneDesc s = tank_scan(5);
    s.sonar.range_bins = 600;
    s.exports.start_time_s = 1767225600 + 3600 + 0.5; // 01:00:00.500 UTC
    const PingSeries p = render_pings(s);
    const ByteMapping m = ping_byte_mapping(s, p);
    const Bytes bytes = encode_ping360_log(s, p, m, "test");
    const Ping360Log log = read_ping360_log(bytes, "test.bin");
    CHECK(log.header == "PingViewer sensor log file");
    CHECK(log.version == 1);
    CHECK(log.sensor_family == 1);
    CHECK(log.sensor_type == 2);
    REQUIRE(log.pings.size() == size_t(p.pings));
    const double c = sound_speed_m_s(s.water.temperature_c, s.water.depth_m);
    // 600 samples over 8 m: 2 x 8 / (600 c 25 ns) ticks.
    const int ticks = int(std::lround(2 * 8 / (600 * c * 25e-9)));
    for (int i = 0; i < p.pings; ++i) {
        const Ping360DeviceData& d = log.pings[size_t(i)];
        INFO("step " << i);
        CHECK(d.mode == 1);
        CHECK(d.angle_grad == (400 - int(std::lround(p.schedule[size_t(i)].head_deg / 0.9))) % 400);
        CHECK(d.sample_period_ticks == ticks);
        CHECK(d.transmit_frequency_khz == 750);
        CHECK(d.number_of_samples == 600);
        CHECK(d.transmit_duration_us ==
              int(std::lround(std::clamp(8000 * 8 / c, 2.5 * ticks * 0.025, 64 * ticks * 0.025))));
        REQUIRE(d.data.size() == 600);
        // The wall at 5 m: the first sample at or above the byte of 10 dB over the noise lies there.
        const int wall = first_bin_at_least(p.profile(i, 0), p.bins, 10);
        REQUIRE(wall >= 0);
        const double sample_m = 8.0 / 600;
        int first = -1;
        for (int j = 0; j < 600 && first < 0; ++j)
            if (d.data[size_t(j)] >= level_byte(p.profile(i, 0)[wall], m) && d.data[size_t(j)] > 0) first = j;
        CHECK(std::abs(first * sample_m - p.grid->bin_near_edge_m(wall)) <= 2 * sample_m);
    }
    CHECK(log.pings[0].timestamp == "01:00:00.500");
    // Outside the protocol: a clear error naming the key.
    s.sonar.frequency_khz = 1200;
    CHECK_THROWS_WITH(encode_ping360_log(s, p, m, "f.json"), Catch::Contains("f.json: sonar.frequency_khz"));
    Bytes cut(bytes.begin(), bytes.end() - 3);
    CHECK_THROWS_WITH(read_ping360_log(cut, "cut.bin"), Catch::Contains("cut.bin"));
}

TEST_CASE("the example scenes of the side-scan and the scanning sonar load and image their targets",
          "[kinds]") {
    SceneDesc ss = load_scene(SONARSIM_ASSETS "/scenes/sidescan_wreck.json");
    REQUIRE(ss.sonar.kind == SonarKind::Sidescan);
    ss.sidescan.pings = 3;
    ss.sonar.pose.position_m[0] = 0; // abeam of the wreck: starboard sees its hull, port bare sand
    const PingSeries p = render_pings(ss);
    auto peak = [&](int ch) {
        float m = -1e30f;
        for (int k = 0; k < p.bins; ++k) m = std::max(m, p.profile(1, ch)[k]);
        return m;
    };
    CHECK(peak(1) > peak(0) + 6);
    SceneDesc sc = load_scene(SONARSIM_ASSETS "/scenes/scan_tank.json");
    REQUIRE(sc.sonar.kind == SonarKind::Scanning);
    sc.scanning.step_deg = 18;
    const PingSeries q = render_pings(sc);
    CHECK(q.pings == 20);
    // Every step meets a wall of the 12.3 x 6.3 m tank within 10 m.
    for (int i = 0; i < q.pings; ++i)
        CHECK(first_bin_at_least(q.ideal_db.data() + size_t(i) * q.bins, q.bins, 10) >= 0);
}

TEST_CASE("pings traced in parallel give the same bytes every time", "[kinds]") {
    SceneDesc s = sidescan_scene(5, 24);
    s.sonar.velocity_mps = {1, 0, 0};
    s.objects = {box({1, 1, 1}, {2, -8, 0.5}, -15)};
    apply_setting(s, "sensor.model", "device", "test");
    s.sensor.elevation_pattern = ElevationPattern::Flat;
    validate_scene(s, "test");
    const PingSeries a = render_pings(s), b = render_pings(s);
    CHECK(a.level_db == b.level_db);
    CHECK(a.ideal_db == b.ideal_db);
    CHECK(a.rays_traced == b.rays_traced);
}

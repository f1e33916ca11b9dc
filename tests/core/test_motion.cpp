// Motion during a frame (sampling/acquisition.hpp): poses along the frame, the interleaved ARIS pings and
// the single ping's range-dependent receive time, each against its closed form.
#include "core/base/errors.hpp"
#include "core/data/pose.hpp"
#include "core/dataset/batch.hpp"
#include "core/data/trajectory.hpp"
#include "core/pipeline/simulator.hpp"
#include "core/sampling/acquisition.hpp"
#include "core/sampling/motion_trace.hpp"
#include "core/scene/params.hpp"
#include "core/scene/sampling_scheme.hpp"
#include "core/scene/scene_io.hpp"
#include "core/shading/physics.hpp"
#include "core/shading/shade.hpp"
#include "support.hpp"

#include <catch2/catch.hpp>
#include <cmath>

using namespace sonarsim;
using test::lin;

namespace {

/// A level sonar 1 m above a floor looking along +x at a thin vertical pole 6 m ahead.
SceneDesc pole_scene() {
    SceneDesc s;
    s.sonar.pose.position_m = {0, 0, 1};
    s.sonar.pose.orientation_deg = {0, 0, 0};
    s.sonar.beams = 128, s.sonar.azimuth_fov_deg = 30, s.sonar.elevation_fov_deg = 14;
    s.sonar.range_min_m = 1, s.sonar.range_max_m = 10, s.sonar.range_bins = 900;
    s.seafloor.reset();
    ObjectDesc pole;
    pole.box_m = Vec3d{0.05, 0.05, 4};
    pole.position_m = {6, 0, 1};
    s.objects.push_back(pole);
    return s;
}

/// Echo energy per beam and per bin (linear).
std::vector<double> per_beam(const PolarImage& img) {
    std::vector<double> e(size_t(img.beams), 0);
    for (int k = 0; k < img.bins; ++k)
        for (int i = 0; i < img.beams; ++i) e[size_t(i)] += lin(img.at(k, i));
    return e;
}
std::vector<double> per_bin(const PolarImage& img) {
    std::vector<double> e(size_t(img.bins), 0);
    for (int k = 0; k < img.bins; ++k)
        for (int i = 0; i < img.beams; ++i) e[size_t(k)] += lin(img.at(k, i));
    return e;
}
double centroid(const std::vector<double>& e) {
    double m = 0, w = 0;
    for (size_t i = 0; i < e.size(); ++i) m += double(i) * e[i], w += e[i];
    return m / w;
}

double sound_speed(const SceneDesc& s) {
    return sound_speed_m_s(s.water.temperature_c, s.water.depth_m);
}

} // namespace

TEST_CASE("poses along a frame follow the body rates and the velocity", "[motion]") {
    SonarParams s;
    s.pose.position_m = {1, 2, 3};
    s.pose.orientation_deg = {0, 0, 20};
    CHECK(pose_at(s, 0.5).orientation_deg == s.pose.orientation_deg); // not moving: the frame's pose
    s.angular_rate_dps = {0, 0, 40};
    s.velocity_mps = {2, 0, 0};
    const Pose p = pose_at(s, 0.25);
    CHECK(p.orientation_deg[2] == Approx(30).margin(1e-9));
    CHECK(p.orientation_deg[0] == Approx(0).margin(1e-9));
    CHECK(p.orientation_deg[1] == Approx(0).margin(1e-9));
    // The velocity is in the sonar's frame at t = 0: 0.5 m along its x, yawed 20 deg.
    CHECK(p.position_m[0] == Approx(1 + 0.5 * std::cos(deg2rad(20))));
    CHECK(p.position_m[1] == Approx(2 + 0.5 * std::sin(deg2rad(20))));
    // Body rates compose: turning for t1 then t2 is turning for t1 + t2, whatever the start orientation.
    s.pose.orientation_deg = {10, -25, 70};
    s.angular_rate_dps = {30, -20, 50};
    SonarParams later = s;
    later.pose = pose_at(s, 0.3);
    const glm::dmat3 a = rotation_matrix(pose_at(later, 0.2).orientation_deg);
    const glm::dmat3 b = rotation_matrix(pose_at(s, 0.5).orientation_deg);
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) CHECK(a[c][r] == Approx(b[c][r]).margin(1e-12));
}

TEST_CASE("ARIS pings: beam i is fired by ping (N - 1 - i) mod P", "[motion]") {
    SonarParams s;
    s.beams = 128, s.pings_per_frame = 8;
    CHECK(ping_of_beam(s, 127) == 0); // device beam 0 (starboard-most) in the first ping
    CHECK(ping_of_beam(s, 0) == 7);
    CHECK(ping_of_beam(s, 127 - 17) == 1);
    s.angular_rate_dps = {0, 0, 10};
    const auto slots = acquisition_slots(s, 1500);
    REQUIRE(slots.size() % 8 == 0);
    CHECK(slots.back().t_tx_s == Approx(7 * (2 * s.range_max_m / 1500 + 420e-6)));
}

TEST_CASE("a sonar that does not move gives today's image, whatever its pings", "[motion]") {
    SceneDesc s = pole_scene();
    Simulator a(s);
    const auto fa = a.render();
    s.sonar.pings_per_frame = 8;
    Simulator b(s);
    const auto fb = b.render();
    CHECK(fa->ideal().level_db == fb->ideal().level_db);
}

TEST_CASE("yawing during a single ping shifts a pole's bearing by omega 2R/c", "[motion]") {
    SceneDesc s = pole_scene();
    const double w_dps = 200;
    s.sonar.angular_rate_dps = {0, 0, w_dps};
    Simulator sim(s);
    const auto f = sim.render();
    const double spacing_deg = s.sonar.azimuth_fov_deg / s.sonar.beams;
    const double t_rx = 2 * 6 / sound_speed(s);
    // Turning to port moves a fixed target to starboard (higher beam index) by omega t.
    const double expected_beam = (s.sonar.azimuth_fov_deg / 2 + w_dps * t_rx) / spacing_deg - 0.5;
    CHECK(centroid(per_beam(f->ideal())) == Approx(expected_beam).margin(0.3));
    Simulator still(pole_scene());
    CHECK(centroid(per_beam(still.render()->ideal())) == Approx(63.5).margin(0.3));
}

TEST_CASE("interleaved ARIS pings see a turning pole in the beams of each ping's time", "[motion]") {
    SceneDesc s = pole_scene();
    const double w_dps = 30;
    s.sonar.angular_rate_dps = {0, 0, w_dps};
    s.sonar.pings_per_frame = 8;
    Simulator sim(s);
    const auto e = per_beam(sim.render()->ideal());
    const double c = sound_speed(s), spacing_deg = s.sonar.azimuth_fov_deg / s.sonar.beams;
    const double pole_half_deg = rad2deg(std::atan(0.025 * std::sqrt(2.0) / 6));
    double peak = 0;
    for (double v : e) peak = std::max(peak, v);
    REQUIRE(peak > 0);
    int seen = 0;
    for (int i = 0; i < s.sonar.beams; ++i) {
        // Where ping k sees the pole: azimuth -omega (t_k + 2R/c).
        const double t = ping_of_beam(s.sonar, i) * ping_interval_s(s.sonar, c) + 2 * 6 / c;
        const double pole_deg = -w_dps * t;
        const double beam_deg = s.sonar.azimuth_fov_deg / 2 - (i + 0.5) * spacing_deg;
        const bool covers = std::abs(beam_deg - pole_deg) < spacing_deg / 2 + pole_half_deg + 0.02;
        if (e[size_t(i)] > 1e-3 * peak) {
            CHECK(covers);
            ++seen;
        }
    }
    CHECK(seen >= 1);
    CHECK(seen <= 4); // the still pole fills 2 beams; its pings now see it in at most a few
}

TEST_CASE("moving toward a wall during a single ping shortens its range by v R / c", "[motion]") {
    // The echo's range is half its two-way path: out from the transmit position, back to the receiver that
    // has moved v 2R/c closer, so R (1 - v / c) to first order.
    SceneDesc s = pole_scene();
    s.objects[0].box_m = Vec3d{0.05, 20, 4};
    s.sonar.range_min_m = 5, s.sonar.range_max_m = 7, s.sonar.range_bins = 400; // 5 mm bins
    const double v = 40;
    Simulator still(s);
    const double r_still = 5 + (centroid(per_bin(still.render()->ideal())) + 0.5) * 0.005;
    s.sonar.velocity_mps = {v, 0, 0};
    Simulator moving_sim(s);
    const double r_moving = 5 + (centroid(per_bin(moving_sim.render()->ideal())) + 0.5) * 0.005;
    const double expected = v * r_still / sound_speed(s);
    CHECK(r_still - r_moving == Approx(expected).margin(0.1 * expected + 0.0025));
}

TEST_CASE("batch takes each frame's velocity and rates from its trajectory", "[motion]") {
    // Frames around a circle of radius 4 m, 10 per turn at 2 Hz, each looking at the centre: the sonar
    // yaws at 360/10 x 2 deg/s and moves one chord per frame, to starboard (counter-clockwise, facing
    // inward) and 18 deg inward of its sideways axis.
    const Trajectory tr = circle_trajectory("0,0,0,4,0,10", 2.0, "test");
    SonarParams s;
    set_motion_from_trajectory(s, tr, 3);
    CHECK(s.angular_rate_dps[2] == Approx(72).margin(1e-9));
    CHECK(s.angular_rate_dps[0] == Approx(0).margin(1e-9));
    const double chord = 2 * 4 * std::sin(deg2rad(18));
    CHECK(s.velocity_mps[0] == Approx(2 * chord * std::sin(deg2rad(18))).epsilon(1e-9));
    CHECK(s.velocity_mps[1] == Approx(-2 * chord * std::cos(deg2rad(18))).epsilon(1e-9));
    CHECK(s.velocity_mps[2] == Approx(0).margin(1e-9));
    set_motion_from_trajectory(s, tr, 9); // the last frame takes the step before it
    CHECK(s.angular_rate_dps[2] == Approx(72).margin(1e-9));
    // batch's frames take them only when the scene asks.
    SceneDesc base;
    CHECK(!moving(frame_scene(base, tr, 3).sonar));
    base.sonar.motion_from_trajectory = true;
    CHECK(frame_scene(base, tr, 3).sonar.angular_rate_dps[2] == Approx(72).margin(1e-9));
}

TEST_CASE("pings per frame must divide the beams", "[motion]") {
    SceneDesc s = pole_scene();
    s.sonar.pings_per_frame = 7;
    try {
        validate_scene(s, "scene.json", {});
        FAIL("accepted 7 pings for 128 beams");
    } catch (const InputError& e) {
        CHECK(std::string(e.what()).find("sonar.pings_per_frame") != std::string::npos);
    }
}

TEST_CASE("a trace of some beams leaves the others empty and traces the rest as a whole trace would",
          "[motion]") {
    SceneDesc s = pole_scene();
    s.seafloor = Seafloor{};
    s.sonar.pose.orientation_deg = {0, 20, 0}; // the floor in view
    const SceneGeometry g(s);
    std::vector<char> every_8th(size_t(s.sonar.beams), 0);
    for (int i = 3; i < s.sonar.beams; i += 8) every_8th[size_t(i)] = 1;
    TraceControl some;
    some.beams = &every_8th;
    // The grid: the same cells in the traced beams, none elsewhere, an eighth of the rays.
    s.sampling.placement = RayPlacement::Grid;
    const TraceResult all = trace(g, s), part = trace(g, s, some);
    CHECK(part.rays_traced * 8 == all.rays_traced);
    for (int i = 0; i < s.sonar.beams; ++i) {
        INFO(i);
        if (!every_8th[size_t(i)]) {
            CHECK(part.cells[size_t(i)].empty());
            continue;
        }
        auto ranges = [&](const TraceResult& t) {
            std::vector<float> r;
            for (const Cell& c : t.cells[size_t(i)]) r.push_back(c.range_m);
            return r;
        };
        CHECK(ranges(part) == ranges(all));
    }
    // Adaptive: the traced beams' image within the tolerance of the whole trace's, the others empty.
    s.sampling.placement = RayPlacement::Adaptive;
    const TraceResult a_all = trace(g, s), a_part = trace(g, s, some);
    CHECK(a_part.rays_traced < a_all.rays_traced / 4);
    const PolarImage img_all = shade(a_all, s), img_part = shade(a_part, s);
    std::vector<double> x, ref;
    for (int k = 0; k < s.sonar.range_bins; ++k)
        for (int i = 0; i < s.sonar.beams; ++i) {
            if (!every_8th[size_t(i)]) {
                if (!std::isinf(img_part.at(k, i))) FAIL("an untraced beam echoes");
                continue;
            }
            x.push_back(lin(img_part.at(k, i))), ref.push_back(lin(img_all.at(k, i)));
        }
    CHECK(test::relative_l1(x, ref) < 0.02);
}

TEST_CASE("a moving ARIS's pings split columns where the nearest beams they trace disagree", "[motion]") {
    // Each ping traces every P-th beam (8 on the ARIS 3000): a beam's neighbours are in other pings. Compared
    // with no neighbour, no beam split in azimuth and the Fig. 9 prism's edges were 0.58 % off (103 holes)
    // against a dense spread reference with the same motion; compared with the nearest beams the ping
    // traces, 0.32 % (32 holes).
    SceneDesc s = load_scene(std::string(SONARSIM_ASSETS) + "/scenes/fig9.json");
    apply_setting(s, "sonar.device", "aris3000-hf", "test");
    apply_setting(s, "sonar.velocity_mps", json::array({0.3, 0, 0}), "test");
    apply_setting(s, "sonar.angular_rate_dps", json::array({0, 0, 10}), "test");
    REQUIRE(s.sonar.pings_per_frame == 8);
    SceneDesc dense = s;
    set_scheme(dense.sampling, SamplingScheme::Spread);
    dense.sampling.elevation_rays = 729, dense.sampling.azimuth_rays = 9;
    auto image = [](const SceneDesc& x) {
        return test::echo_intensity(Simulator(x).render()->ideal(), x.sonar.noise_level_db);
    };
    const double err = test::relative_l1(image(s), image(dense));
    INFO("rel L1 against spread 729 x 9: " << err);
    CHECK(err < 0.0045);
}

TEST_CASE("a moving frame's error estimate weighs each slot by its echo", "[motion]") {
    // Two slabs: one with a tenth of the echo estimated at 10 %, one at 1 %; and a slab with no echo,
    // whatever it estimates. The frame's rel L1 is their |error| over their echo: (0.1 + 9 x 0.01) / 10.
    // Its median: the slots' medians by echoing bins (10 bins at 0.5 dB, 30 at 0.05 dB: 0.05 dB). The part
    // across the beams (fast's azimuth probe) is weighed as rel L1 is: (0.05 + 9 x 0.005) / 10.
    using detail::SlotEstimate;
    auto slot = [](double rel, double median_db, double echo, double bins) {
        SlotEstimate x;
        x.e.valid = true, x.e.rel_l1 = rel, x.e.median_abs_db = median_db, x.e.p95_abs_db = 2 * median_db;
        x.e.passes = 1, x.echo = echo, x.bins = bins, x.e.azimuth_rel_l1 = rel / 2;
        return x;
    };
    std::vector<SlotEstimate> v = {slot(0.1, 0.5, 1, 10), slot(0.01, 0.05, 9, 30), slot(0.5, 3, 0, 0)};
    v[1].e.passes = 3;
    const auto e = detail::combine_slot_estimates(v);
    CHECK(e.valid);
    CHECK(e.rel_l1 == Approx(0.019));
    CHECK(e.azimuth_rel_l1 == Approx(0.0095));
    CHECK(e.median_abs_db == Approx(0.05));
    CHECK(e.p95_abs_db == Approx(6)); // the largest
    CHECK(e.passes == 3);
    // No echo at all: the largest of each.
    const auto none = detail::combine_slot_estimates({slot(0.1, 0.5, 0, 0), slot(0.2, 0.1, 0, 0)});
    CHECK(none.rel_l1 == Approx(0.2));
    CHECK(none.azimuth_rel_l1 == Approx(0.1));
    CHECK(none.median_abs_db == Approx(0.5));
}

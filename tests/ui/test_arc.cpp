// Pixel <-> 3D: the elevation arc of a sector-image pixel maps back onto that pixel; the points that echo
// into a pixel lie in its beam and range bin.
#include "ui/model/image_views.hpp"
#include "ui/model/sonar_geometry.hpp"

#include "core/display/image.hpp"
#include "core/data/pose.hpp"
#include "core/scene/scene_io.hpp"
#include "core/shading/physics.hpp"
#include "core/pipeline/simulator.hpp"

#include <catch2/catch.hpp>

using namespace sonarsim;
using namespace sonarsim::ui;

TEST_CASE("every point of a pixel's elevation arc lands on that pixel", "[ui][arc]") {
    const SceneDesc s = default_scene();
    const SectorLayout L(s.sonar, default_sector_height(s.sonar));
    int checked = 0;
    for (double px : {40.5, 100.25, 150.3, 250.75})
        for (double py : {30.5, 200.5, 380.25, 500.5}) {
            const auto place = sector_pixel_place(L, s.sonar, px, py);
            if (!place) continue;
            const auto arc = elevation_arc(s.sonar, place->range_m, place->azimuth_deg, 25);
            REQUIRE(arc.size() == 25);
            for (const auto& p : arc) {
                const PointInImage q = locate_world_point(s.sonar, L, p);
                CHECK(q.in_view);
                CHECK(q.px == Approx(px).margin(1e-6));
                CHECK(q.py == Approx(py).margin(1e-6));
                CHECK(q.bin == place->bin);
                CHECK(q.beam == place->beam);
            }
            CHECK(locate_world_point(s.sonar, L, arc.front()).elevation_deg ==
                  Approx(s.sonar.elevation_fov_deg / 2));
            CHECK(locate_world_point(s.sonar, L, arc.back()).elevation_deg ==
                  Approx(-s.sonar.elevation_fov_deg / 2));
            ++checked;
        }
    CHECK(checked >= 8);
    CHECK_FALSE(sector_pixel_place(L, s.sonar, 1.0, 1.0)); // a corner outside the fan
}

TEST_CASE("raw polar pixels map to their bin and beam", "[ui][arc]") {
    const SceneDesc s = default_scene();
    auto p = polar_pixel_place(s.sonar, 0.5, 0.5); // top-left: port-most beam, farthest bin
    REQUIRE(p);
    CHECK(p->beam == 0);
    CHECK(p->bin == s.sonar.range_bins - 1);
    p = polar_pixel_place(s.sonar, s.sonar.beams - 0.5, s.sonar.range_bins - 0.5);
    REQUIRE(p);
    CHECK(p->beam == s.sonar.beams - 1);
    CHECK(p->bin == 0);
    CHECK_FALSE(polar_pixel_place(s.sonar, -1, 3));
}

TEST_CASE("the surface points echoing into the prism's pixel lie in that cell", "[ui][arc]") {
    const SceneDesc s = default_scene();
    Simulator sim(s);
    const auto f = sim.render();
    const SectorLayout L(s.sonar, f->sector().height);
    // The pixel of the prism's front face (towards the sonar), where it echoes.
    const glm::dvec3 pos = to_glm(s.sonar.pose.position_m);
    const glm::dvec3 centre(1.5, 1.5, 0.11);
    const glm::dvec3 front =
        centre + 0.03 * glm::normalize(glm::dvec3(pos.x - centre.x, pos.y - centre.y, 0));
    const PointInImage q = locate_world_point(s.sonar, L, front);
    REQUIRE(q.in_view);
    const auto pts = echoing_points(f->hits(), s, q.bin, q.beam);
    REQUIRE(!pts.empty());
    const double dr = (s.sonar.range_max_m - s.sonar.range_min_m) / s.sonar.range_bins;
    const double r0 = s.sonar.range_min_m + q.bin * dr;
    for (const auto& p : pts) {
        const PointInImage e = locate_world_point(s.sonar, L, p);
        CHECK(e.beam == q.beam);
        // A cell spreads its echo over its range footprint: its centre lies within a few bins.
        CHECK(e.range_m > r0 - 0.05);
        CHECK(e.range_m < r0 + dr + 0.05);
    }
    CHECK(std::isfinite(f->polar().at(q.bin, q.beam)));
}

TEST_CASE("image helpers: polar colour image, tick steps, A-scan", "[ui][image]") {
    PolarImage img;
    img.bins = 3, img.beams = 2;
    img.level_db = {-INFINITY, 100, 80, 120, 90, 110};
    DisplayParams d;
    d.lo_db = 80, d.hi_db = 120;
    const Image8 c = polar_color_image(img, d);
    REQUIRE(c.width == 2);
    REQUIRE(c.height == 3);
    CHECK(int(c.pixels[0]) == 64);                // top-left: bin 2, beam 0 = 90 dB
    CHECK(int(c.pixels[(2 * 2 + 1) * 3]) == 128); // bottom-right: bin 0 beam 1 = 100 dB
    CHECK(int(c.pixels[(2 * 2 + 0) * 3]) == no_echo_rgb(Colormap::Gray)[0]); // -inf: the no-echo colour
    CHECK(nice_step(4.5, 5) == Approx(1.0));
    CHECK(nice_step(32, 4) == Approx(10.0));
    CHECK(nice_step(40, 6) == Approx(5.0));
    CHECK(beam_levels(img, 1) == std::vector<float>{100, 120, 110});
    CHECK(beam_levels(img, 2).empty());
}

TEST_CASE("the fields of view drawn: a side-scan's swaths at the ping heard from the sonar's pose, a scan's "
          "beam at its sector's first step and at the head's newest",
          "[ui][arc][kinds]") {
    SceneDesc side = default_scene();
    apply_setting(side, "sonar.kind", "sidescan", "test");
    side.sonar.pose = {{0, 0, 3}, {0, 0, 0}};
    side.sonar.velocity_mps = {1, 0, 0};
    validate_scene(side, "test");
    auto fovs = fields_of_view(side); // its own pings: the first is heard from the sonar's pose
    REQUIRE(fovs.size() == 2);
    CHECK(fovs[0].pose.position_m == side.sonar.pose.position_m);
    CHECK(fovs[0].pose.orientation_deg[2] == Approx(90));  // port
    CHECK(fovs[1].pose.orientation_deg[2] == Approx(-90)); // starboard
    const Trajectory line = {{0.0, {{0, 0, 3}, {0, 0, 0}}}, {10.0, {{10, 0, 3}, {0, 0, 0}}}};
    const auto along = ping_schedule_along(side, line, 4.0);
    fovs = fields_of_view(side, &along); // along a track: the newest, at the playback time
    REQUIRE(fovs.size() == 2);
    CHECK(fovs[0].pose.position_m[0] == along.back().vehicle.position_m[0]);
    CHECK(fovs[0].pose.position_m[0] == Approx(4.0).margin(0.1));

    SceneDesc scan = default_scene();
    apply_setting(scan, "sonar.kind", "scanning", "test");
    scan.sonar.pose = {{0, 0, 3}, {0, 0, 0}};
    scan.scanning.sector_start_deg = -60, scan.scanning.sector_end_deg = 60, scan.scanning.step_deg = 30;
    validate_scene(scan, "test");
    fovs = fields_of_view(scan);
    REQUIRE(fovs.size() == 2);
    CHECK(fovs[0].pose.orientation_deg[2] == Approx(-60));
    CHECK(fovs[1].pose.orientation_deg[2] == Approx(60));
    const double dt =
        kind_ping_interval_s(scan, sound_speed_m_s(scan.water.temperature_c, scan.water.depth_m));
    const auto steps = ping_schedule_along(scan, line, 7.2 * dt);
    REQUIRE(steps.back().number == 7); // the sweep's step 2: neither end of the sector
    fovs = fields_of_view(scan, &steps);
    REQUIRE(fovs.size() == 2);
    CHECK(fovs[0].pose.orientation_deg[2] == Approx(-60));
    CHECK(fovs[1].pose.orientation_deg[2] == Approx(steps.back().head_deg));
}

// The default camera (a new scene, F) and terrain: every shipped scene is framed from an oblique view above
// with the sonar unhidden and its field of view on screen; the Monterey tile is terrain, the ship is not.
#include "ui/model/framing.hpp"
#include "ui/model/interaction.hpp"
#include "ui/model/sonar_geometry.hpp"

#include "core/data/pose.hpp"
#include "core/geometry/geometry.hpp"
#include "core/scene/scene_io.hpp"

#include <catch2/catch.hpp>
#include <string>

using namespace sonarsim;
using namespace sonarsim::ui;

namespace {

SceneDesc shipped(const std::string& name) {
    return load_scene(std::string(SONARSIM_SOURCE_DIR) + "/assets/scenes/" + name);
}

std::vector<Box3> bounds_of(const SceneDesc& s, const SceneGeometry& g) {
    std::vector<std::shared_ptr<const TriMesh>> local;
    for (size_t i = 0; i < g.object_count(); ++i) local.push_back(g.local_mesh(i));
    return object_bounds(s, local);
}

} // namespace

TEST_CASE("the Monterey tile is terrain, the ship and the Fig. 9 prism are not", "[ui][framing]") {
    const SceneDesc m = shipped("monterey.json"), w = shipped("shipwreck.json");
    const SceneGeometry gm(m), gw(w);
    const auto bm = bounds_of(m, gm), bw = bounds_of(w, gw);
    REQUIRE(bm.size() == 1);
    CHECK(bm[0].size().x == Approx(974).margin(2));
    CHECK(is_terrain(bm[0], m.sonar));
    CHECK_FALSE(is_terrain(bw[0], w.sonar));
    const SceneDesc d = default_scene();
    CHECK_FALSE(is_terrain(bounds_of(d, SceneGeometry(d))[0], d.sonar));
}

TEST_CASE("the default camera looks down on the sonar, unhidden, with its field of view in view",
          "[ui][framing]") {
    for (const char* name : {"monterey.json", "shipwreck.json", "tank.json", "fig9.json"}) {
        CAPTURE(name);
        const SceneDesc s = shipped(name);
        const SceneGeometry g(s);
        const double aspect = 700.0 / 980.0; // the 3D view of a 1600 x 1000 window
        const OrbitCamera cam = default_camera(s, bounds_of(s, g), aspect);
        const int h = 600, w = int(h * aspect);
        // Oblique, from above the sonar.
        CHECK(cam.elevation_deg >= 30);
        CHECK(cam.elevation_deg <= 60);
        const glm::dvec3 sonar = to_glm(s.sonar.pose.position_m);
        CHECK(cam.eye().z > sonar.z + 0.2 * s.sonar.range_max_m);
        // The sonar and the far corners of its field of view (those above the floor) project inside the view.
        std::vector<glm::dvec3> pts{sonar};
        for (double a : {-1.0, 1.0}) {
            glm::dvec3 c = sonar_point(s.sonar, s.sonar.range_max_m, a * s.sonar.azimuth_fov_deg / 2, 0);
            if (s.seafloor && c.z < s.seafloor->height_m) { // where the boresight plane meets the floor
                const double t = (sonar.z - s.seafloor->height_m) / (sonar.z - c.z);
                c = sonar + t * (c - sonar);
            }
            pts.push_back(c);
        }
        for (const glm::dvec3& p : pts) {
            glm::dvec2 px;
            REQUIRE(cam.project(p, w, h, px));
            CHECK(px.x > 0);
            CHECK(px.x < w);
            CHECK(px.y > 0);
            CHECK(px.y < h);
        }
        // Nothing stands between the eye and the sonar (no wall of terrain in front of the camera).
        const Ray ray{cam.eye(), glm::normalize(sonar - cam.eye())};
        const auto hit = pick_surface(ray, g, s.seafloor);
        CHECK((!hit || hit->t > glm::length(sonar - cam.eye()) - 0.01));
        // The sonar is not a speck: its field of view spans at least a fifth of the view's width.
        glm::dvec2 a, b;
        REQUIRE(cam.project(pts[1], w, h, a));
        REQUIRE(cam.project(pts[2], w, h, b));
        glm::dvec2 o;
        REQUIRE(cam.project(sonar, w, h, o));
        const double span = std::max({glm::length(a - b), glm::length(a - o), glm::length(b - o)});
        CHECK(span > 0.2 * w);
    }
}

// Orbit camera: rays through pixels and projection of points are inverse of each other; the --orbit path
// and its statistics.
#include "ui/model/camera.hpp"
#include "ui/model/orbit.hpp"

#include "core/data/pose.hpp"
#include "core/scene/scene_io.hpp"

#include <catch2/catch.hpp>

using namespace sonarsim::ui;

TEST_CASE("a ray through a pixel projects back onto that pixel", "[ui][camera]") {
    OrbitCamera cam;
    cam.target = {1.5, 1.5, 0.1};
    cam.distance_m = 3.0;
    cam.azimuth_deg = 200, cam.elevation_deg = 30;
    const int w = 640, h = 480;
    for (auto px : {glm::dvec2(10, 20), glm::dvec2(320, 240), glm::dvec2(600, 470)}) {
        const Ray r = cam.ray_through(px.x, px.y, w, h);
        CHECK(glm::length(r.dir) == Approx(1.0));
        glm::dvec2 back;
        REQUIRE(cam.project(r.origin + 2.5 * r.dir, w, h, back));
        CHECK(back.x == Approx(px.x).margin(1e-6));
        CHECK(back.y == Approx(px.y).margin(1e-6));
    }
    // The centre pixel looks at the target.
    const Ray c = cam.ray_through(w / 2.0, h / 2.0, w, h);
    CHECK(glm::length(glm::cross(c.dir, cam.target - c.origin)) == Approx(0).margin(1e-9));
}

TEST_CASE("orbit, pan and zoom keep the camera sane", "[ui][camera]") {
    OrbitCamera cam;
    const glm::dvec3 t0 = cam.target;
    cam.orbit(100, 5000); // elevation clamps below the pole
    CHECK(cam.elevation_deg <= 89.0);
    const double d0 = cam.distance_m;
    cam.zoom(1);
    CHECK(cam.distance_m < d0);
    cam.pan(10, 0, 500);
    CHECK(glm::length(cam.target - t0) > 0);
    CHECK(cam.target.z == Approx(t0.z).margin(1e-9 + 0.5)); // panning sideways barely changes height
}

TEST_CASE("ray_plane finds the crossing in front of the ray only", "[ui][camera]") {
    double t = 0;
    REQUIRE(ray_plane({{0, 0, 2}, {0, 0, -1}}, {5, 5, 0}, {0, 0, 1}, t));
    CHECK(t == Approx(2));
    CHECK_FALSE(ray_plane({{0, 0, 2}, {0, 0, 1}}, {5, 5, 0}, {0, 0, 1}, t));
    CHECK_FALSE(ray_plane({{0, 0, 2}, {1, 0, 0}}, {5, 5, 0}, {0, 0, 1}, t));
}

TEST_CASE("the orbit path keeps the sonar looking at the same point while it moves", "[ui][orbit]") {
    const sonarsim::SceneDesc s = sonarsim::default_scene();
    const Orbiter orbit(s);
    CHECK(orbit.at(0).position_m[0] == Approx(s.sonar.pose.position_m[0]));
    CHECK(orbit.at(0).orientation_deg[2] == Approx(s.sonar.pose.orientation_deg[2]));
    for (int k : {1, 7, 100, 240}) {
        const sonarsim::Pose p = orbit.at(k);
        const glm::dvec3 bore = sonarsim::rotation_matrix(p.orientation_deg) * glm::dvec3(1, 0, 0);
        const glm::dvec3 to_centre = glm::normalize(orbit.centre() - sonarsim::to_glm(p.position_m));
        CHECK(glm::dot(bore, to_centre) == Approx(1.0).margin(1e-9));
        CHECK(p.position_m != orbit.at(k - 1).position_m); // a new pose every frame: a retrace
        CHECK(std::abs(p.orientation_deg[2]) <= 180.0);
    }
}

TEST_CASE("frame statistics: mean, nearest-rank p95, start-up frame left out", "[ui][orbit]") {
    FrameStats st;
    st.frame_ms = {500};
    for (int i = 1; i <= 20; ++i) st.frame_ms.push_back(i);
    st.image_ms = {4, 6};
    CHECK(st.json_line(1) ==
          "{\"frames\":20,\"frame_ms_mean\":10.50,\"frame_ms_p95\":19.00,\"image_ms_mean\":5.00,"
          "\"image_ms_p95\":6.00,\"images\":\"full\"}");
    st.preview = true;
    CHECK(st.json_line(1).find("\"images\":\"preview\"") != std::string::npos);
}

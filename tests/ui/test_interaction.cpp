// Picking and dragging the frustum; a drag moves the prism's echo across the image.
#include "ui/model/interaction.hpp"
#include "ui/model/sonar_geometry.hpp"

#include "core/base/pose.hpp"
#include "core/scene/scene_io.hpp"
#include "core/pipeline/simulator.hpp"

#include <catch2/catch.hpp>

using namespace sonarsim;
using namespace sonarsim::ui;

namespace {

Ray ray_to(const glm::dvec3& eye, const glm::dvec3& p) {
    return {eye, glm::normalize(p - eye)};
}

/// Mean beam index of the traced hits on object 0 (material 1), or -1 if none.
double prism_beam(const SceneDesc& scene) {
    Simulator sim(scene);
    const auto f = sim.render();
    double sum = 0, n = 0;
    for (int i = 0; i < f->hits().beams; ++i)
        for (const Cell& c : f->hits().cells[size_t(i)])
            if (c.material == 1) sum += i, n += 1;
    return n > 0 ? sum / n : -1;
}

} // namespace

TEST_CASE("ray_triangle hits inside, misses outside and behind", "[ui][pick]") {
    const glm::dvec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
    auto t = ray_triangle({{0.2, 0.2, 1}, {0, 0, -1}}, a, b, c);
    REQUIRE(t);
    CHECK(*t == Approx(1));
    CHECK_FALSE(ray_triangle({{0.8, 0.8, 1}, {0, 0, -1}}, a, b, c));
    CHECK_FALSE(ray_triangle({{0.2, 0.2, 1}, {0, 0, 1}}, a, b, c));
}

TEST_CASE("pick_surface finds the prism before the floor, and the floor elsewhere", "[ui][pick]") {
    const SceneDesc s = default_scene();
    const SceneGeometry geometry(s);
    auto hit = pick_surface(ray_to({1.5, 1.5, 2}, {1.5, 1.5, 0}), geometry, s.seafloor);
    REQUIRE(hit);
    CHECK(hit->material == 1);
    CHECK(hit->point.z == Approx(0.22).margin(1e-5));
    hit = pick_surface(ray_to({3, 3, 2}, {3, 3, 0}), geometry, s.seafloor);
    REQUIRE(hit);
    CHECK(hit->material == 0);
    CHECK(hit->point.z == Approx(0).margin(1e-9));
}

TEST_CASE("translating keeps the grabbed point under the cursor", "[ui][drag]") {
    const SceneDesc s = default_scene();
    const glm::dvec3 eye(-1, 4, 3);
    const glm::dvec3 grab = sonar_point(s.sonar, 1.0, 0, 0);
    const Ray r0 = ray_to(eye, grab);
    const FrustumDrag d =
        begin_drag(DragMode::Translate, s.sonar.pose, r0, glm::length(grab - eye), {100, 100});
    const glm::dvec3 target = grab + glm::dvec3(0.3, -0.2, 0);
    const Pose p = drag_pose(d, ray_to(eye, target), {130, 90});
    CHECK(p.position_m[0] == Approx(s.sonar.pose.position_m[0] + 0.3).margin(1e-9));
    CHECK(p.position_m[1] == Approx(s.sonar.pose.position_m[1] - 0.2).margin(1e-9));
    CHECK(p.position_m[2] == Approx(s.sonar.pose.position_m[2]).margin(1e-12));
    CHECK(p.orientation_deg == s.sonar.pose.orientation_deg);
}

TEST_CASE("vertical drags move only z, rotation drags turn by the mouse motion", "[ui][drag]") {
    const SceneDesc s = default_scene();
    const glm::dvec3 eye(-1, 4, 1);
    const glm::dvec3 grab = sonar_point(s.sonar, 1.0, 0, 0);
    const FrustumDrag v =
        begin_drag(DragMode::Vertical, s.sonar.pose, ray_to(eye, grab), glm::length(grab - eye), {0, 0});
    const Pose up = drag_pose(v, ray_to(eye, grab + glm::dvec3(0, 0, 0.25)), {0, -30});
    CHECK(up.position_m[2] == Approx(s.sonar.pose.position_m[2] + 0.25).margin(1e-9));
    CHECK(up.position_m[0] == s.sonar.pose.position_m[0]);
    CHECK(up.position_m[1] == s.sonar.pose.position_m[1]);

    const Ray any = ray_to(eye, grab);
    const FrustumDrag yp = begin_drag(DragMode::YawPitch, s.sonar.pose, any, 1.0, {50, 50});
    const Pose turned = drag_pose(yp, any, {90, 30}); // 40 px right, 20 px up
    CHECK(turned.orientation_deg[2] == Approx(s.sonar.pose.orientation_deg[2] - 40 * kDegPerPixel));
    CHECK(turned.orientation_deg[1] == Approx(s.sonar.pose.orientation_deg[1] - 20 * kDegPerPixel));
    CHECK(turned.position_m == s.sonar.pose.position_m);

    const FrustumDrag rl = begin_drag(DragMode::Roll, s.sonar.pose, any, 1.0, {0, 0});
    const Pose rolled = drag_pose(rl, any, {2000, 0}); // far: the angle wraps into [-180, 180]
    CHECK(rolled.orientation_deg[0] >= -180.0);
    CHECK(rolled.orientation_deg[0] <= 180.0);
}

TEST_CASE("dragging the frustum sideways moves the prism's echo across the fan", "[ui][drag]") {
    SceneDesc s = default_scene();
    const double before = prism_beam(s);
    REQUIRE(before >= 0);
    // Drag 0.25 m to the sonar's starboard (its -y axis, projected on the floor plane): the prism moves to
    // port in the image, i.e. towards lower beam indices.
    const glm::dvec3 starboard = rotation_matrix(s.sonar.pose.orientation_deg) * glm::dvec3(0, -1, 0);
    const glm::dvec3 move = 0.25 * glm::normalize(glm::dvec3(starboard.x, starboard.y, 0));
    const glm::dvec3 eye(-1, 4, 3), grab = sonar_point(s.sonar, 1.0, 0, 0);
    const FrustumDrag d =
        begin_drag(DragMode::Translate, s.sonar.pose, ray_to(eye, grab), glm::length(grab - eye), {0, 0});
    s.sonar.pose = drag_pose(d, ray_to(eye, grab + move), {10, 0});
    const double after = prism_beam(s);
    REQUIRE(after >= 0);
    const Polar p = world_to_sonar_polar(s.sonar.pose, {1.5, 1.5, 0.11});
    const double expected_beam =
        (s.sonar.azimuth_fov_deg / 2 - p.azimuth_deg) / (s.sonar.azimuth_fov_deg / s.sonar.beams);
    CHECK(after < before - 10);
    CHECK(after == Approx(expected_beam).margin(4));
}

// Picking and dragging the frustum; a drag moves the prism's echo across the image.
#include "ui/model/interaction.hpp"
#include "ui/model/sonar_geometry.hpp"

#include "core/grid/sonar_grid.hpp"
#include "core/scene/params.hpp"
#include "core/data/pose.hpp"
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

TEST_CASE("a translation seen at a grazing angle moves what the cursor covers at the grabbed depth",
          "[ui][drag]") {
    // Monterey-like: the camera 2 m above the sonar's plane, 200 m away; a 5 px drag upwards meets the
    // plane some 500 m away.
    SceneDesc s = default_scene();
    OrbitCamera cam;
    cam.target =
        glm::dvec3(s.sonar.pose.position_m[0], s.sonar.pose.position_m[1], s.sonar.pose.position_m[2]);
    cam.distance_m = 200;
    cam.elevation_deg = 0.6;
    const int w = 800, h = 600;
    glm::dvec2 px0;
    REQUIRE(cam.project(cam.target, w, h, px0));
    const Ray r0 = cam.ray_through(px0.x, px0.y, w, h);
    const double t0 = glm::length(cam.target - cam.eye());
    const double m_px = metres_per_px(cam, r0, t0, h);
    CHECK(m_px == Approx(2 * 200 * std::tan(glm::radians(22.5)) / h).epsilon(1e-3));
    const FrustumDrag d = begin_drag(DragMode::Translate, s.sonar.pose, r0, t0, px0, m_px);
    const glm::dvec2 px1 = px0 + glm::dvec2(0, -5);
    const Pose p = drag_pose(d, cam.ray_through(px1.x, px1.y, w, h), px1);
    const double moved = std::hypot(p.position_m[0] - s.sonar.pose.position_m[0],
                                    p.position_m[1] - s.sonar.pose.position_m[1]);
    CHECK(moved == Approx(kMaxDragStretch * 5 * m_px).epsilon(1e-6)); // limited: the plane's hit is far
    CHECK(moved < 10); // where the plane is met: some 300 m from the grabbed point
    CHECK(p.position_m[2] == s.sonar.pose.position_m[2]);
    // Above the horizon the ray misses the plane: the sonar still moves away from the camera, as far.
    const glm::dvec2 px2 = px0 + glm::dvec2(0, -200);
    const Pose q = drag_pose(d, cam.ray_through(px2.x, px2.y, w, h), px2);
    const glm::dvec3 away = glm::normalize(glm::dvec3(cam.forward().x, cam.forward().y, 0));
    const glm::dvec3 dq(q.position_m[0] - s.sonar.pose.position_m[0],
                        q.position_m[1] - s.sonar.pose.position_m[1], 0);
    CHECK(glm::length(dq) == Approx(kMaxDragStretch * 200 * m_px).epsilon(1e-6));
    CHECK(glm::dot(dq, away) > 0.99 * glm::length(dq));
}

TEST_CASE("the 3D frustum and its floor footprint span a beam table's own fan, not +-fov/2",
          "[ui][geometry]") {
    // The DIDSON's table fan spans -14.72 ... +14.09 deg: the shell and the footprint reach exactly its
    // edges.
    SceneDesc s = default_scene();
    apply_setting_text(s, "sonar.device=didson300-hf", "test");
    const std::shared_ptr<const SonarGrid> grid_ptr =
        sonar_grid(s.sonar); // held: the registry keeps only what someone holds
    const SonarGrid& grid = *grid_ptr;
    // Its table's outer edges (assets/devices/beam_tables/didson300_hf_96.csv): not symmetric.
    REQUIRE(grid.port_edge_deg() + grid.starboard_edge_deg() < -0.5);
    auto azimuth_span = [&](const std::vector<glm::vec3>& points) {
        double lo = 1e9, hi = -1e9;
        for (const glm::vec3& p : points) {
            const Polar q = world_to_sonar_polar(s.sonar.pose, {p.x, p.y, p.z});
            if (q.range_m < 1e-3) continue; // the apex
            lo = std::min(lo, q.azimuth_deg), hi = std::max(hi, q.azimuth_deg);
        }
        return std::pair(lo, hi);
    };
    const auto [lo, hi] = azimuth_span(frustum_shell(s.sonar, 8, 4).triangles);
    CHECK(lo == Approx(grid.starboard_edge_deg()).margin(1e-3));
    CHECK(hi == Approx(grid.port_edge_deg()).margin(1e-3));
    const auto [flo, fhi] = azimuth_span(floor_footprint(s.sonar, 0.0, 64));
    CHECK(flo == Approx(grid.starboard_edge_deg()).margin(1e-3));
    CHECK(fhi == Approx(grid.port_edge_deg()).margin(1e-3));
}

#include "ui/model/framing.hpp"

#include "ui/model/sonar_geometry.hpp"

#include "core/grid/sonar_grid.hpp"
#include "core/data/pose.hpp"

#include <algorithm>
#include <cmath>

namespace sonarsim::ui {

Box3 placed_bounds(const TriMesh& local, const glm::dmat4& transform) {
    if (local.vertices.empty()) {
        const glm::dvec3 o(transform[3]);
        return {o, o};
    }
    glm::dvec3 lo(local.vertices[0]), hi(lo);
    for (const glm::vec3& v : local.vertices)
        lo = glm::min(lo, glm::dvec3(v)), hi = glm::max(hi, glm::dvec3(v));
    Box3 b{glm::dvec3(1e300), glm::dvec3(-1e300)};
    for (int k = 0; k < 8; ++k) {
        const glm::dvec3 c(k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z);
        const glm::dvec3 w(transform * glm::dvec4(c, 1));
        b.lo = glm::min(b.lo, w), b.hi = glm::max(b.hi, w);
    }
    return b;
}

std::vector<Box3> object_bounds(const SceneDesc& scene,
                                const std::vector<std::shared_ptr<const TriMesh>>& local) {
    std::vector<Box3> out;
    for (size_t i = 0; i < scene.objects.size() && i < local.size(); ++i)
        if (local[i]) out.push_back(placed_bounds(*local[i], object_transform(scene.objects[i])));
    return out;
}

bool is_terrain(const Box3& b, const SonarParams& sonar) {
    const double narrow = std::min(b.size().x, b.size().y);
    return narrow >= std::min(kTerrainExtentM, 2 * sonar.range_max_m);
}

OrbitCamera default_camera(const SceneDesc& scene, const std::vector<Box3>& objects, double aspect) {
    const SonarParams& s = scene.sonar;
    // What must be in view: the sonar, its field of view out to r_max (or down to the floor), the floor
    // patch it sees and the objects (terrain only near the sonar).
    std::vector<glm::dvec3> pts;
    for (const glm::vec3& v : sonar_body(s).vertices) pts.emplace_back(v);
    const std::shared_ptr<const SonarGrid> grid_ptr =
        sonar_grid(s); // held: the registry keeps only what someone holds
    const SonarGrid& grid = *grid_ptr;
    for (double a : {grid.starboard_edge_deg(), 0.0, grid.port_edge_deg()})
        for (double e : {-1.0, 1.0}) {
            glm::dvec3 p = sonar_point(s, s.range_max_m, a, e * grid.elevation_half_deg());
            if (scene.seafloor && p.z < scene.seafloor->height_m) continue; // the floor patch stands for it
            pts.push_back(p);
        }
    if (scene.seafloor)
        for (const glm::vec3& p : floor_footprint(s, scene.seafloor->height_m, 8)) pts.emplace_back(p);
    const glm::dvec3 at = to_glm(s.pose.position_m);
    const double reach = kFrameReach * s.range_max_m;
    for (const Box3& b : objects) {
        Box3 c = b;
        if (is_terrain(b, s)) { // only the part around the sonar
            c.lo = glm::max(b.lo, glm::dvec3(at.x - reach, at.y - reach, b.lo.z));
            c.hi = glm::min(b.hi, glm::dvec3(at.x + reach, at.y + reach, b.hi.z));
            if (c.lo.x > c.hi.x || c.lo.y > c.hi.y) continue;
        }
        for (int k = 0; k < 8; ++k)
            pts.emplace_back(k & 1 ? c.hi.x : c.lo.x, k & 2 ? c.hi.y : c.lo.y, k & 4 ? c.hi.z : c.lo.z);
    }
    glm::dvec3 lo = pts[0], hi = pts[0];
    for (auto& p : pts) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const glm::dvec3 bore = rotation_matrix(s.pose.orientation_deg) * glm::dvec3(1, 0, 0);
    OrbitCamera cam;
    cam.target = 0.5 * (lo + hi);
    cam.azimuth_deg = std::atan2(bore.y, bore.x) * 180.0 / kPi + 180.0 + 35.0; // behind, off to starboard
    cam.elevation_deg = 40.0;
    // The nearest distance at which every point projects inside the central 86% of the viewport.
    const int h = 600, w = std::max(1, int(h * aspect));
    auto fits = [&](double d) {
        cam.distance_m = d;
        for (auto& p : pts) {
            glm::dvec2 px;
            if (glm::dot(p - cam.eye(), cam.forward()) < 1e-3 * d || !cam.project(p, w, h, px) ||
                px.x < 0.07 * w || px.x > 0.93 * w || px.y < 0.07 * h || px.y > 0.93 * h)
                return false;
        }
        return true;
    };
    double near_m = 0.2, far_m = 1.2 * kMaxCameraDistanceM;
    for (int i = 0; i < 50; ++i) {
        const double mid = std::sqrt(near_m * far_m);
        (fits(mid) ? far_m : near_m) = mid;
    }
    cam.distance_m = std::min(far_m, kMaxCameraDistanceM);
    return cam;
}

} // namespace sonarsim::ui

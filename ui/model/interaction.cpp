#include "ui/model/interaction.hpp"

#include "core/geometry/geometry.hpp"
#include "ui/model/sonar_geometry.hpp"

#include <algorithm>
#include <cmath>

namespace sonarsim::ui {

std::optional<double> ray_triangle(const Ray& ray, const glm::dvec3& a, const glm::dvec3& b,
                                   const glm::dvec3& c) {
    const glm::dvec3 e1 = b - a, e2 = c - a, p = glm::cross(ray.dir, e2);
    const double det = glm::dot(e1, p);
    if (std::abs(det) < 1e-14) return std::nullopt;
    const double inv = 1 / det;
    const glm::dvec3 s = ray.origin - a;
    const double u = glm::dot(s, p) * inv;
    if (u < 0 || u > 1) return std::nullopt;
    const glm::dvec3 q = glm::cross(s, e1);
    const double v = glm::dot(ray.dir, q) * inv;
    if (v < 0 || u + v > 1) return std::nullopt;
    const double t = glm::dot(e2, q) * inv;
    if (t <= 1e-9) return std::nullopt;
    return t;
}

namespace {

double wrap180(double deg) {
    deg = std::fmod(deg + 180.0, 360.0);
    if (deg < 0) deg += 360.0;
    return deg - 180.0;
}

} // namespace

std::optional<SurfaceHit> pick_surface(const Ray& ray, const SceneGeometry& geometry,
                                       const std::optional<Seafloor>& floor) {
    std::optional<SurfaceHit> best;
    if (auto h = geometry.intersect(ray.origin, ray.dir, 1e6))
        best = SurfaceHit{ray.origin + h->t * ray.dir, h->t, h->material};
    if (floor)
        if (auto h = intersect_floor(*floor, ray.origin, ray.dir, 1e6))
            if (!best || h->t < best->t) best = SurfaceHit{ray.origin + h->t * ray.dir, h->t, kFloorMaterial};
    return best;
}

FrustumDrag begin_drag(DragMode mode, const Pose& pose, const Ray& ray, double t_grab,
                       const glm::dvec2& mouse_px) {
    FrustumDrag d;
    d.mode = mode;
    d.start_pose = pose;
    d.grab = ray.origin + t_grab * ray.dir;
    d.start_px = mouse_px;
    if (mode == DragMode::Vertical) {
        glm::dvec3 h(ray.dir.x, ray.dir.y, 0);
        d.plane_n = glm::length(h) > 1e-9 ? glm::normalize(h) : glm::dvec3(1, 0, 0);
    } else {
        d.plane_n = glm::dvec3(0, 0, 1);
    }
    return d;
}

Pose drag_pose(const FrustumDrag& d, const Ray& ray, const glm::dvec2& mouse_px) {
    Pose p = d.start_pose;
    const glm::dvec2 delta = mouse_px - d.start_px;
    switch (d.mode) {
    case DragMode::Translate:
    case DragMode::Vertical: {
        double t = 0;
        if (!ray_plane(ray, d.grab, d.plane_n, t) || t > 1e4) return p;
        const glm::dvec3 move = ray.origin + t * ray.dir - d.grab;
        if (d.mode == DragMode::Translate) {
            p.position_m[0] += move.x;
            p.position_m[1] += move.y;
        } else {
            p.position_m[2] += move.z;
        }
        break;
    }
    case DragMode::YawPitch:
        p.orientation_deg[2] = wrap180(p.orientation_deg[2] - kDegPerPixel * delta.x);
        p.orientation_deg[1] = std::clamp(p.orientation_deg[1] + kDegPerPixel * delta.y, -90.0, 90.0);
        break;
    case DragMode::Roll:
        p.orientation_deg[0] = wrap180(p.orientation_deg[0] + kDegPerPixel * delta.x);
        break;
    }
    return p;
}

} // namespace sonarsim::ui

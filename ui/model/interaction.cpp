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

/// Farther than any scene: a drag ray that meets its plane beyond this, or not at all, stops here.
constexpr double kFarM = 1e7;

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

double metres_per_px(const OrbitCamera& camera, const Ray& ray, double t_m, double view_h_px) {
    const double depth_m = t_m * std::abs(glm::dot(ray.dir, camera.forward()));
    return view_h_px > 0 ? 2 * depth_m * std::tan(glm::radians(camera.fov_y_deg) / 2) / view_h_px : 0.0;
}

FrustumDrag begin_drag(DragMode mode, const Pose& pose, const Ray& ray, double t_grab,
                       const glm::dvec2& mouse_px, double metres_per_px) {
    FrustumDrag d;
    d.metres_per_px = metres_per_px;
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
    const glm::dvec2 delta = d.fine * (mouse_px - d.start_px);
    switch (d.mode) {
    case DragMode::Translate:
    case DragMode::Vertical: {
        double t = 0;
        // Where the ray meets the drag plane; a ray above the horizon goes as far along it as it can.
        if (!ray_plane(ray, d.grab, d.plane_n, t) || t > kFarM) {
            if (!(d.metres_per_px > 0)) return p;
            t = kFarM;
        }
        glm::dvec3 move = ray.origin + t * ray.dir - d.grab;
        move -= glm::dot(move, d.plane_n) * d.plane_n;
        const double limit_m = kMaxDragStretch * d.metres_per_px * glm::length(delta);
        move *= d.fine;
        if (d.metres_per_px > 0 && glm::length(move) > limit_m) move *= limit_m / glm::length(move);
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

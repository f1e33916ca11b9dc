#include "ui/model/camera.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace sonarsim::ui {
namespace {
constexpr double kDeg = 3.14159265358979323846 / 180.0;
}

glm::dvec3 OrbitCamera::eye() const {
    const double a = azimuth_deg * kDeg, e = elevation_deg * kDeg;
    return target +
           distance_m * glm::dvec3(std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e));
}

glm::dvec3 OrbitCamera::forward() const {
    return glm::normalize(target - eye());
}

glm::dmat4 OrbitCamera::view() const {
    return glm::lookAt(eye(), target, glm::dvec3(0, 0, 1));
}

glm::dmat4 OrbitCamera::projection(double aspect) const {
    const double near_m = std::max(1e-3, distance_m * 0.01), far_m = distance_m * 50 + 50;
    return glm::perspective(fov_y_deg * kDeg, aspect, near_m, far_m);
}

Ray OrbitCamera::ray_through(double px, double py, int w, int h) const {
    const double x = 2 * px / w - 1, y = 1 - 2 * py / h;
    const glm::dmat4 inv = glm::inverse(projection(double(w) / h) * view());
    glm::dvec4 a = inv * glm::dvec4(x, y, -1, 1), b = inv * glm::dvec4(x, y, 1, 1);
    const glm::dvec3 pa = glm::dvec3(a) / a.w, pb = glm::dvec3(b) / b.w;
    return {eye(), glm::normalize(pb - pa)};
}

bool OrbitCamera::project(const glm::dvec3& world, int w, int h, glm::dvec2& px) const {
    const glm::dvec4 c = projection(double(w) / h) * view() * glm::dvec4(world, 1);
    if (c.w <= 1e-9) return false;
    px = {(c.x / c.w + 1) * 0.5 * w, (1 - c.y / c.w) * 0.5 * h};
    return true;
}

void OrbitCamera::orbit(double dx, double dy) {
    azimuth_deg = std::fmod(azimuth_deg - 0.3 * dx, 360.0);
    elevation_deg = std::clamp(elevation_deg + 0.3 * dy, -89.0, 89.0);
}

void OrbitCamera::pan(double dx, double dy, int viewport_h) {
    const glm::dvec3 f = forward();
    const glm::dvec3 right = glm::normalize(glm::cross(f, glm::dvec3(0, 0, 1)));
    const glm::dvec3 up = glm::cross(right, f);
    const double m_per_px = 2 * distance_m * std::tan(fov_y_deg * kDeg / 2) / std::max(1, viewport_h);
    target += (-dx * right + dy * up) * m_per_px;
}

void OrbitCamera::zoom(double steps) {
    distance_m = std::clamp(distance_m * std::pow(0.88, steps), 0.05, kMaxCameraDistanceM);
}

bool ray_plane(const Ray& ray, const glm::dvec3& point, const glm::dvec3& n, double& t) {
    const double d = glm::dot(ray.dir, n);
    if (std::abs(d) < 1e-12) return false;
    t = glm::dot(point - ray.origin, n) / d;
    return t > 0;
}

} // namespace sonarsim::ui

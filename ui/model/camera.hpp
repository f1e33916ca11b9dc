// Orbit camera of the 3D view (world z up). Non-GL: view/projection matrices, rays through pixels, projection
// of world points to pixels. Pixel coordinates have their origin at the viewport's top-left corner.
#pragma once
#include <glm/glm.hpp>

namespace sonarsim::ui {

/// Farthest the camera goes from its target [m] (a kilometre-wide terrain tile fits).
constexpr double kMaxCameraDistanceM = 5000.0;

struct Ray {
    glm::dvec3 origin;
    glm::dvec3 dir; ///< unit length
};

struct OrbitCamera {
    glm::dvec3 target{1.2, 1.8, 0.2}; ///< point orbited around [m]
    double distance_m = 4.0;          ///< eye to target [m]
    double azimuth_deg = -60.0;       ///< direction from the target to the eye, about +z from +x [deg]
    double elevation_deg = 35.0;      ///< eye height angle above the target's horizontal plane [deg]
    double fov_y_deg = 45.0;

    glm::dvec3 eye() const;
    /// Unit view direction (eye -> target).
    glm::dvec3 forward() const;
    glm::dmat4 view() const;
    glm::dmat4 projection(double aspect) const;

    /// Ray from the eye through pixel (px, py) of a w x h viewport.
    Ray ray_through(double px, double py, int w, int h) const;
    /// World point -> pixel of a w x h viewport; false when it lies behind the eye.
    bool project(const glm::dvec3& world, int w, int h, glm::dvec2& px) const;

    /// Mouse gestures: rotate by a pixel delta, pan the target in the view plane, zoom by wheel steps.
    void orbit(double dx_px, double dy_px);
    void pan(double dx_px, double dy_px, int viewport_h);
    void zoom(double wheel_steps);
};

/// Distance t along the ray to the plane through `point` with normal `n`; false when the ray is parallel
/// to it or meets it behind its origin.
bool ray_plane(const Ray& ray, const glm::dvec3& point, const glm::dvec3& n, double& t);

} // namespace sonarsim::ui

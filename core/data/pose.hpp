// Frames and pose (SONAR_MODEL.md): world z up; sonar x forward, y port, z up; R = Rz(yaw) Ry(pitch)
// Rx(roll).
#pragma once
#include "core/data/scene.hpp"

#include <cmath>
#include <glm/glm.hpp>
#include <vector>

namespace sonarsim {

constexpr double kPi = 3.14159265358979323846;
inline double deg2rad(double d) {
    return d * kPi / 180.0;
}
inline double rad2deg(double r) {
    return r * 180.0 / kPi;
}
inline glm::dvec3 to_glm(const Vec3d& v) {
    return {v[0], v[1], v[2]};
}

/// R = Rz(yaw) Ry(pitch) Rx(roll) (paper eq. 12), angles [deg] as {roll, pitch, yaw}.
glm::dmat3 rotation_matrix(const Vec3d& orientation_deg);

/// Roll, pitch, yaw [deg] of a rotation R = Rz(yaw) Ry(pitch) Rx(roll) (the inverse of rotation_matrix;
/// pitch in [-90, 90]).
Vec3d orientation_of(const glm::dmat3& rotation);

/// Unit direction of azimuth a, elevation e [rad] in the sonar frame: (cos e cos a, cos e sin a, sin e).
inline glm::dvec3 sonar_direction(double azimuth_rad, double elevation_rad) {
    const double ce = std::cos(elevation_rad);
    return {ce * std::cos(azimuth_rad), ce * std::sin(azimuth_rad), std::sin(elevation_rad)};
}

/// Range and azimuth [deg] and elevation [deg] of a world point as seen by the sonar.
struct Polar {
    double range_m, azimuth_deg, elevation_deg;
};
Polar world_to_sonar_polar(const Pose& pose, const glm::dvec3& point_world);

} // namespace sonarsim

#include "core/data/pose.hpp"

#include <algorithm>

namespace sonarsim {

glm::dmat3 rotation_matrix(const Vec3d& o) {
    const double r = deg2rad(o[0]), p = deg2rad(o[1]), y = deg2rad(o[2]);
    const double cr = std::cos(r), sr = std::sin(r), cp = std::cos(p), sp = std::sin(p), cy = std::cos(y),
                 sy = std::sin(y);
    // glm is column-major: m[col][row]. Rows of eq. 12.
    glm::dmat3 m;
    m[0][0] = cp * cy, m[1][0] = -cr * sy + cy * sp * sr, m[2][0] = sr * sy + cr * cy * sp;
    m[0][1] = cp * sy, m[1][1] = cr * cy + sp * sr * sy, m[2][1] = -cy * sr + cr * sp * sy;
    m[0][2] = -sp, m[1][2] = cp * sr, m[2][2] = cp * cr;
    return m;
}

Vec3d orientation_of(const glm::dmat3& R) {
    // glm: m[col][row].
    return {rad2deg(std::atan2(R[1][2], R[2][2])), rad2deg(std::asin(std::clamp(-R[0][2], -1.0, 1.0))),
            rad2deg(std::atan2(R[0][1], R[0][0]))};
}

Polar world_to_sonar_polar(const Pose& pose, const glm::dvec3& p) {
    const glm::dvec3 local =
        glm::transpose(rotation_matrix(pose.orientation_deg)) * (p - to_glm(pose.position_m));
    const double r = glm::length(local);
    return {r, rad2deg(std::atan2(local.y, local.x)),
            rad2deg(std::atan2(local.z, std::hypot(local.x, local.y)))};
}

} // namespace sonarsim

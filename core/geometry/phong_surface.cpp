#include "core/geometry/phong_surface.hpp"

#include <cmath>

namespace sonarsim {

PhongPoint phong_point(const glm::dvec3 p[3], const glm::dvec3 n[3], double u, double v, double alpha) {
    const double b[3] = {1 - u - v, u, v};
    const double db_du[3] = {-1, 1, 0}, db_dv[3] = {-1, 0, 1};
    const glm::dvec3 e_u = p[1] - p[0], e_v = p[2] - p[0]; // dP/du, dP/dv
    const glm::dvec3 flat = b[0] * p[0] + b[1] * p[1] + b[2] * p[2];
    // offset = -alpha sum_i b_i s_i n_i with s_i = (P - p_i) . n_i, the flat point's height over corner i's
    // tangent plane; its derivatives follow from ds_i/du = e_u . n_i, ds_i/dv = e_v . n_i.
    glm::dvec3 offset(0), d_du(0), d_dv(0);
    for (int i = 0; i < 3; ++i) {
        const double s = glm::dot(flat - p[i], n[i]);
        offset += (b[i] * s) * n[i];
        d_du += (db_du[i] * s + b[i] * glm::dot(e_u, n[i])) * n[i];
        d_dv += (db_dv[i] * s + b[i] * glm::dot(e_v, n[i])) * n[i];
    }
    PhongPoint out;
    out.offset = -alpha * offset;
    out.point = flat + out.offset;
    out.d_du = e_u - alpha * d_du, out.d_dv = e_v - alpha * d_dv;
    return out;
}

std::optional<PhongHit> phong_hit(const glm::dvec3 p[3], const glm::dvec3 n[3], double u, double v,
                                  double alpha, const glm::dvec3& o, const glm::dvec3& d, double t) {
    constexpr int kSteps = 6;
    constexpr double kNear = 0.5; // (u, v) may leave the triangle by half its size (onto the neighbour's)
    const double tolerance = 1e-9 * (glm::length(p[1] - p[0]) + glm::length(p[2] - p[0]));
    const glm::dvec3 m = -d;
    for (int k = 0; k < kSteps; ++k) {
        const PhongPoint c = phong_point(p, n, u, v, alpha);
        const glm::dvec3 normal = glm::cross(c.d_du, c.d_dv);
        // Solve d_du du + d_dv dv - d dt = o + t d - P* (Cramer's rule).
        const glm::dvec3 r = o + t * d - c.point;
        const double det = glm::dot(normal, m);
        if (!(std::abs(det) > 1e-9 * glm::length(normal) * glm::length(d))) return std::nullopt;
        const double du = glm::dot(glm::cross(r, c.d_dv), m) / det;
        const double dv = glm::dot(glm::cross(c.d_du, r), m) / det;
        const double dt = glm::dot(normal, r) / det;
        if (std::abs(dt) * glm::length(d) < tolerance) return PhongHit{t + dt, normal};
        u += du, v += dv, t += dt;
        if (!(u > -kNear && v > -kNear && 1 - u - v > -kNear) || !std::isfinite(t)) return std::nullopt;
    }
    return std::nullopt; // not settled
}

} // namespace sonarsim

// Curved hits on a smooth mesh: Phong tessellation (Boubekeur & Alexa 2008, "Phong Tessellation"). A flat
// triangle's point is pulled towards the tangent planes of its corners, so a coarse sphere's hits lie on a
// curved surface through its vertices instead of on its flat faces, which lie up to a face's depth inside.
#pragma once
#include <glm/glm.hpp>
#include <optional>

namespace sonarsim {

/// A point of a triangle's Phong surface.
struct PhongPoint {
    glm::dvec3 point{0};         ///< the curved point P*
    glm::dvec3 offset{0};        ///< P* - P, from the flat point
    glm::dvec3 d_du{0}, d_dv{0}; ///< dP*/du, dP*/dv: the tangent plane, normal cross(d_du, d_dv)
};

/// The Phong surface at barycentric (u, v) of the triangle p[0], p[1], p[2] (flat point
/// P = (1 - u - v) p0 + u p1 + v p2) with unit corner normals n[0..2]:
///   P* = (1 - alpha) P + alpha sum_i b_i proj_i(P),  proj_i(P) = P - ((P - p_i) . n_i) n_i,
/// b = (1 - u - v, u, v), alpha the shape factor in [0, 1] (0: the flat triangle). Where all three corner
/// normals are one normal n, sum_i b_i (P - p_i) . n = (P - P) . n = 0: the face does not move (an edge of
/// a crease or a flat part of a mesh). On a sphere (n_i = p_i / R) the surface lies (2 alpha - 1) times
/// the flat face's depth h from the sphere, to second order in the face's size: alpha = 1/2 follows it,
/// alpha = 1 bulges out by as much as the face falls short.
PhongPoint phong_point(const glm::dvec3 p[3], const glm::dvec3 n[3], double u, double v, double alpha);

/// Where a ray meets the Phong surface.
struct PhongHit {
    double t = 0;         ///< range along the ray (in units of |d|)
    glm::dvec3 normal{0}; ///< the surface's normal there, cross(dP*/du, dP*/dv) (not normalised)
};

/// Where the ray o + t d meets the Phong surface near its hit at barycentric (u, v), range t, on the flat
/// triangle: Newton's method on P*(u, v) = o + t d from there (the first step meets the tangent plane at
/// P*; each further step corrects for its curvature). Empty when the steps do not settle within a few
/// iterations near the triangle (the ray grazes the surface, or it folds).
std::optional<PhongHit> phong_hit(const glm::dvec3 p[3], const glm::dvec3 n[3], double u, double v,
                                  double alpha, const glm::dvec3& o, const glm::dvec3& d, double t);

} // namespace sonarsim

// Internal to the tracers (trace.cpp, adaptive.cpp): one ray's first hit and the cell it stands for.
#pragma once
#include "core/geometry/geometry.hpp"
#include "core/data/pose.hpp"
#include "core/grid/sonar_grid.hpp"
#include "core/grid/sensor_patterns.hpp"
#include "core/sampling/trace.hpp"

#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

namespace sonarsim::detail {

/// An angle [rad] with its cosine and sine.
struct Angle {
    double rad = 0, c = 1, s = 0;
    Angle() = default;
    explicit Angle(double r) : rad(r), c(std::cos(r)), s(std::sin(r)) {}
    /// base + sign * step by the angle-sum identities (no sine or cosine evaluated); r is that angle [rad].
    Angle(double r, const Angle& base, const Angle& step, int sign)
        : rad(r), c(base.c * step.c - sign * base.s * step.s), s(base.s * step.c + sign * base.c * step.s) {}
};

/// The sonar's frame and the reach of its rays.
struct RayFrame {
    glm::dmat3 R;
    glm::dvec3 origin;
    double t_max; ///< rays reaching past r_max can still spread part of their cell into the window
    ElevationWeight elevation_weight;      ///< the sensor's elevation pattern (1 for the hard aperture)
    std::shared_ptr<const SonarGrid> grid; ///< the beams' azimuths and edges
    explicit RayFrame(const SceneDesc& s)
        : R(rotation_matrix(s.sonar.pose.orientation_deg)), origin(to_glm(s.sonar.pose.position_m)),
          t_max(s.sonar.range_max_m * 1.05), elevation_weight(s), grid(sonar_grid(s.sonar)) {}
    glm::dvec3 dir(const Angle& a, const Angle& e) const { return R * glm::dvec3(e.c * a.c, e.c * a.s, e.s); }
};

/// Range at which direction d from o meets the plane through p with normal n; -1 if it does not. Inline:
/// the criteria call it once per edge (make_cell does the same for its four edges in the sonar's frame).
inline double plane_range(const glm::dvec3& o, const glm::dvec3& p, const glm::dvec3& n,
                          const glm::dvec3& d) {
    const double den = glm::dot(n, d);
    const double t = glm::dot(n, p - o) / den;
    return (den != 0 && t > 0 && std::isfinite(t)) ? t : -1;
}

/// plane_range for a direction d known only to within ~1e-14 of the exact one (angles by the angle-sum
/// identities instead of sin and cos): the exact call's sign (-1 when it misses) and its value to a relative
/// 1e-7, or NaN when d is too close to the plane (or the plane to o) to say; the caller then takes the exact
/// direction. Lets a criterion decide from cheap directions without changing any decision.
inline double plane_range_near(const glm::dvec3& o, const glm::dvec3& p, const glm::dvec3& n,
                               const glm::dvec3& d) {
    // |d - d_exact| < 1e-14 moves n.d by as much: with |n.d| > 1e-6 its sign is the exact one and t moves by
    // a relative 1e-8 at most; with 1e-9 < |n.(p - o)| < 1e12 the exact t is finite and nonzero.
    const double den = glm::dot(n, d), num = glm::dot(n, p - o);
    if (!(std::abs(den) > 1e-6) || !(std::abs(num) > 1e-9 && std::abs(num) < 1e12))
        return std::numeric_limits<double>::quiet_NaN();
    const double t = num / den;
    return t > 0 ? t : -1;
}

/// The n + 1 edges of n even cells over [-phi / 2, phi / 2] [rad], top down (`centres`: their n centres).
std::vector<Angle> even_angles(double phi, int n, bool centres = false);

/// Angle(de / 2), from a small per-thread cache: the adaptive sampler's cells come in a few widths.
const Angle& half_angle(double de);

/// First hit against the floor plane and the meshes (meshes skipped when the ray misses their bounds).
std::optional<Hit> first_hit(const SceneGeometry& g, const SceneDesc& s, const glm::dvec3& o,
                             const glm::dvec3& d, double t_max);

/// The cell [a_lo, a_hi] x [e_lo, e_hi] around the ray (a, e) that hit `h`: range, incidence (h.normal: the
/// shading normal), solid angle (weighted by the elevation pattern) and the range footprint at the cell's
/// edges on the plane of the face hit (h.face_normal).
/// `centre`: the cell's centre direction (azimuth, elevation) when the ray is not at it (jittered): the
/// footprint is then the whole cell's on that plane, wherever in the cell the ray fell.
Cell make_cell(const RayFrame& f, const Hit& h, const Angle& a, const Angle& e, const Angle& a_lo,
               const Angle& a_hi, const Angle& e_lo, const Angle& e_hi,
               const std::pair<Angle, Angle>* centre = nullptr);

} // namespace sonarsim::detail

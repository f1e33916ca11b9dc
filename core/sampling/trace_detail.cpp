#include "core/sampling/trace_detail.hpp"

#include "core/base/recent_values.hpp"

#include <algorithm>
#include <limits>
#include <utility>

namespace sonarsim::detail {

std::optional<Hit> first_hit(const SceneGeometry& g, const SceneDesc& s, const glm::dvec3& o,
                             const glm::dvec3& d, double t_max) {
    std::optional<Hit> out;
    if (s.seafloor)
        if ((out = intersect_floor(*s.seafloor, o, d, t_max))) t_max = out->t;
    if (s.water.surface_height_m)
        if (auto h = intersect_surface(*s.water.surface_height_m, o, d, t_max)) out = h, t_max = h->t;
    if (!g.has_meshes()) return out;
    // Slab test against the scene bounds first: most rays of a typical scene only see the floor.
    double t0 = 0, t1 = t_max;
    const glm::dvec3 lo = g.bounds_lo(), hi = g.bounds_hi();
    for (int k = 0; k < 3 && t0 <= t1; ++k) {
        if (d[k] == 0) {
            if (o[k] < lo[k] || o[k] > hi[k]) return out;
            continue;
        }
        double a = (lo[k] - o[k]) / d[k], b = (hi[k] - o[k]) / d[k];
        if (a > b) std::swap(a, b);
        t0 = std::max(t0, a), t1 = std::min(t1, b);
    }
    if (t0 > t1) return out;
    if (auto m = g.intersect(o, d, t_max)) out = m;
    return out;
}

const Angle& half_angle(double de) {
    return recent_value<8>(de, [](double w) { return Angle(w / 2); });
}

Cell make_cell(const RayFrame& f, const Hit& h, const Angle& a, const Angle& e, const Angle& a_lo,
               const Angle& a_hi, const Angle& e_lo, const Angle& e_hi, const std::pair<Angle, Angle>* centre) {
    const glm::dvec3 d = f.dir(a, e), p = f.origin + h.t * d;
    Cell c;
    c.point_m = glm::vec3(p);
    c.range_m = float(h.t);
    c.cos_incidence = float(std::min(1.0, std::abs(glm::dot(h.normal, d))));
    c.solid_angle_sr = float(e.c * (e_hi.rad - e_lo.rad) * (a_hi.rad - a_lo.rad) * f.elevation_weight(e.rad));
    c.azimuth_rad = float(a.rad), c.azimuth_width_rad = float(a_hi.rad - a_lo.rad);
    c.elevation_rad = float(e.rad), c.elevation_width_rad = float(e_hi.rad - e_lo.rad);
    // The footprint lies on the face the ray hit, where the neighbouring rays land too: a smooth object's
    // shading normal changes how strongly it echoes (the incidence above), not where it is.
    // Each edge ray o + r d_k meets that plane at r = n.(p - o) / n.d_k (plane_range), with n.d_k taken in
    // the sonar's frame as (R^T n).(cos e cos a, cos e sin a, sin e): one product with R, not one per edge.
    const glm::dvec3& n = h.face_normal;
    const glm::dvec3 n_sonar = n * f.R; // R^T n
    const double num = glm::dot(n, p - f.origin);
    auto edge_range = [&](const Angle& ak, const Angle& ek) {
        const double den = n_sonar.x * (ek.c * ak.c) + n_sonar.y * (ek.c * ak.s) + n_sonar.z * ek.s;
        const double t = num / den;
        return (den != 0 && t > 0 && std::isfinite(t)) ? t : -1;
    };
    // Off-centre ray: the edges through the cell's centre lines, about the range at its centre.
    const double r_centre = centre ? edge_range(centre->first, centre->second) : -1;
    const bool centred = r_centre > 0;
    const Angle& fa = centred ? centre->first : a;
    const Angle& fe = centred ? centre->second : e;
    const double r = centred ? r_centre : h.t;
    const double re0 = edge_range(fa, e_lo);
    const double re1 = edge_range(fa, e_hi);
    const double ra0 = edge_range(a_lo, fe);
    const double ra1 = edge_range(a_hi, fe);
    // An edge that does not meet the plane (beyond its horizon): mirror the other edge about r. An edge ray
    // close to the plane's horizon meets it far away (the range grows as 1 / (n.d), without bound): the
    // facet does not reach that far, and the echo spread there would land in bins no surface crosses (a
    // cell 7 m away at grazing incidence spread from 4 to 19 m). Such an edge keeps at most kMaxAsymmetry
    // times the other edge's offset from r (on a plane away from its horizon the two differ by a few %).
    constexpr double kMaxAsymmetry = 2;
    auto edge = [r](double x, double other) {
        if (!(x > 0)) return float(other > 0 ? 2 * r - other : r);
        if (!(other > 0)) return float(x);
        const double lim = kMaxAsymmetry * std::abs(other - r);
        return float(r + std::clamp(x - r, -lim, lim));
    };
    c.range_e_lo_m = edge(re0, re1), c.range_e_hi_m = edge(re1, re0);
    // The azimuth edges count from range_m (footprint_of): shifted by the ray's range from the centre's.
    const double shift = h.t - r;
    c.range_a_lo_m = float(edge(ra0, ra1) + shift), c.range_a_hi_m = float(edge(ra1, ra0) + shift);
    c.material = h.material;
    c.elevation_index = 0;
    return c;
}

} // namespace sonarsim::detail

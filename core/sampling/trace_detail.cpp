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

std::vector<Angle> even_angles(double phi, int n, bool centres) {
    const double d = phi / n, offset = centres ? 0.5 : 0.0;
    std::vector<Angle> out(size_t(n) + (centres ? 0 : 1));
    for (size_t j = 0; j < out.size(); ++j) out[j] = Angle(phi / 2 - (double(j) + offset) * d);
    return out;
}

const Angle& half_angle(double de) {
    return recent_value<8>(de, [](double w) { return Angle(w / 2); });
}

Cell make_cell(const RayFrame& f, const Hit& h, const Angle& a, const Angle& e, const Angle& a_lo,
               const Angle& a_hi, const Angle& e_lo, const Angle& e_hi,
               const std::pair<Angle, Angle>* centre) {
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
    // An edge that does not meet the plane (beyond its horizon): mirror the other edge about r. An edge ray
    // close to the plane's horizon meets it far away (the range grows as 1 / (n.d), without bound): the
    // facet does not reach that far, and the echo spread there would land in bins no surface crosses (a
    // cell 7 m away at grazing incidence spread from 4 to 19 m). Such an edge keeps at most kMaxAsymmetry
    // times the other edge's offset from r (on a plane away from its horizon the two differ by a few %).
    constexpr double kMaxAsymmetry = 2;
    // The footprint's four edges [m] through the lines of the cell at (fa, fe), about range r there.
    struct Edges {
        double e_lo, e_hi, a_lo, a_hi;
    };
    auto edges = [&](const Angle& fa, const Angle& fe, double r) {
        auto edge = [r](double x, double other) {
            if (!(x > 0)) return other > 0 ? 2 * r - other : r;
            if (!(other > 0)) return x;
            const double lim = kMaxAsymmetry * std::abs(other - r);
            return r + std::clamp(x - r, -lim, lim);
        };
        const double re0 = edge_range(fa, e_lo), re1 = edge_range(fa, e_hi);
        const double ra0 = edge_range(a_lo, fe), ra1 = edge_range(a_hi, fe);
        return Edges{edge(re0, re1), edge(re1, re0), edge(ra0, ra1), edge(ra1, ra0)};
    };
    // An off-centre ray (jittered) stands for the whole cell: its footprint is taken through the cell's
    // centre lines, about the range at the centre (the azimuth edges count from range_m, the ray's range,
    // so they shift by its offset), when that footprint covers the ray's own range; it does not on a plane
    // seen nearly edge-on, whose centre line meets it far from the ray (the ray's own footprint then).
    auto centred = [&](Edges& x) {
        const double r_c = edge_range(centre->first, centre->second);
        if (!(r_c > 0)) return false;
        x = edges(centre->first, centre->second, r_c);
        const double lo = std::min(x.e_lo, x.e_hi) + std::min(x.a_lo, x.a_hi) - r_c;
        const double hi = std::max(x.e_lo, x.e_hi) + std::max(x.a_lo, x.a_hi) - r_c;
        const double slack = 1e-6 * h.t;
        x.a_lo += h.t - r_c, x.a_hi += h.t - r_c;
        return h.t >= lo - slack && h.t <= hi + slack;
    };
    Edges x;
    if (!centre || !centred(x)) x = edges(a, e, h.t);
    c.range_e_lo_m = float(x.e_lo), c.range_e_hi_m = float(x.e_hi);
    c.range_a_lo_m = float(x.a_lo), c.range_a_hi_m = float(x.a_hi);
    c.material = h.material;
    c.elevation_index = 0;
    return c;
}

} // namespace sonarsim::detail

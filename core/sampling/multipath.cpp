#include "core/sampling/multipath.hpp"

#include "core/data/pose.hpp"
#include "core/shading/footprint.hpp"
#include "core/shading/shade.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace sonarsim::detail {

bool multipath_active(const SceneDesc& s) {
    if (s.sampling.bounces <= 0) return false;
    if (s.water.surface_height_m) return true;
    if (s.seafloor && s.seafloor->material.is_mirror()) return true;
    return std::any_of(s.objects.begin(), s.objects.end(), [](auto& o) { return o.material.is_mirror(); });
}

Multipath::Multipath(const SceneGeometry& g, const SceneDesc& s, const RayFrame& f)
    : g_(g), s_(s), f_(f), image_start_(f), k_(shade_constants(s)),
      half_azimuth_rad_(f.grid->half_aperture_rad()),
      half_elevation_rad_(f.elevation_weight.traced_fov_rad() / 2) {
    image_start_.grid.reset();
}

bool Multipath::is_mirror(unsigned m) const {
    return m == kSurfaceMaterial || material_of(s_, m).is_mirror();
}

int Multipath::beam_of(double a) const {
    return f_.grid->beam_of_azimuth_rad(a);
}

namespace {
/// A start this far along the ray from a surface does not hit that surface again (Embree works in single
/// precision) [m].
double offset_m(const glm::dvec3& p) {
    return 1e-5 * (1 + std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}));
}
/// The range interval a cell's echo is spread over [m] (shading's footprint law).
double range_lo_m(const Cell& c) {
    return footprint_of(c).lo;
}
double range_hi_m(const Cell& c) {
    return footprint_of(c).hi();
}
} // namespace

glm::dvec3 Multipath::reflect(RayFrame& image, const Hit& hit, const Angle& a, const Angle& e,
                              glm::dvec3& d2) const {
    const glm::dvec3 d = image.dir(a, e), x = image.origin + hit.t * d, n = hit.normal;
    const glm::dmat3 H = glm::dmat3(1.0) - 2.0 * glm::outerProduct(n, n); // reflection in the mirror
    image.R = H * image.R;
    image.origin = x + H * (image.origin - x);
    d2 = H * d;
    return x;
}

Multipath::Continuation Multipath::continuation(const Hit& h, const Angle& a, const Angle& e) const {
    Continuation c;
    if (!is_mirror(h.material)) return c;
    c.reflected = true;
    RayFrame image = image_start_;
    glm::dvec3 d2;
    const glm::dvec3 x = reflect(image, h, a, e, d2);
    if ((c.hit = trace_on(x, d2, h.t))) c.cos_at_hit = std::min(1.0, std::abs(glm::dot(c.hit->normal, d2)));
    return c;
}

std::optional<Hit> Multipath::trace_on(const glm::dvec3& x, const glm::dvec3& d2, double travelled) const {
    const double eps = offset_m(x);
    auto next = first_hit(g_, s_, x + eps * d2, d2, 2 * f_.t_max - travelled - eps);
    if (next) next->t += travelled + eps;
    return next;
}

std::uint64_t Multipath::ghosts(const Hit& h, const Angle& a, const Angle& e, const Angle& a_lo,
                                const Angle& a_hi, const Angle& e_lo, const Angle& e_hi, int beam,
                                std::vector<GhostCell>& out, const Continuation* first) const {
    RayFrame image = image_start_; // the sonar mirrored in each mirror of the chain so far
    Hit hit = h;                   // t: path length from the image sonar
    GhostCell chain;
    std::uint64_t rays = 0;
    for (int k = 0; k < s_.sampling.bounces && is_mirror(hit.material); ++k) {
        glm::dvec3 d2;
        const glm::dvec3 x = reflect(image, hit, a, e, d2);
        chain.mirror_material[k] = hit.material;
        chain.mirror_cos[k] = float(std::min(1.0, std::abs(glm::dot(hit.normal, d2))));
        chain.mirror_point_m[k] = glm::vec3(x);
        const bool known = k == 0 && first;
        rays += known ? 0 : 1;
        const std::optional<Hit> next = known ? first->hit : trace_on(x, d2, hit.t);
        if (!next) break;
        hit = *next;
        rays += emit(image, hit, k + 1, chain, a, e, a_lo, a_hi, e_lo, e_hi, beam, out,
                     known ? &first->direct_leg_blocked : nullptr);
    }
    return rays;
}

std::uint64_t Multipath::emit(const RayFrame& image, const Hit& hit, int k, const GhostCell& chain,
                              const Angle& a, const Angle& e, const Angle& a_lo, const Angle& a_hi,
                              const Angle& e_lo, const Angle& e_hi, int ray_beam, std::vector<GhostCell>& out,
                              std::int8_t* blocked) const {
    const Cell c = make_cell(image, hit, a, e, a_lo, a_hi, e_lo, e_hi);
    GhostCell g = chain;
    g.cell = c;
    // Double path: out and back by the mirrors, along the ray (in its beam, as mixed paths back by the
    // mirrors); the image sonar's monostatic echo.
    if (hit.t <= f_.t_max) {
        g.other_leg_m = c.range_m, g.cos_other = c.cos_incidence;
        g.tx_bounces = g.rx_bounces = std::uint8_t(k);
        g.beam = std::uint32_t(ray_beam);
        if (!negligible(g, ray_beam, ray_beam, range_lo_m(c), range_hi_m(c))) out.push_back(g);
    }
    // Mixed paths need the scatterer to see the sonar, within the aperture.
    const glm::dvec3 p = image.origin + hit.t * image.dir(a, e);
    glm::dvec3 v = f_.origin - p;
    const double r1 = glm::length(v);
    if (!(r1 > 0) || 0.5 * (hit.t + r1) > f_.t_max) return 0;
    v /= r1;
    const glm::dvec3 u = glm::transpose(f_.R) * -v; // the scatterer's direction, sonar frame
    const double a_p = std::atan2(u.y, u.x), e_p = std::asin(std::clamp(u.z, -1.0, 1.0));
    if (std::abs(a_p) > half_azimuth_rad_ || std::abs(e_p) > half_elevation_rad_) return 0;
    const double b_ray = f_.elevation_weight(e.rad), b_p = f_.elevation_weight(e_p);
    if (!(b_p > 0) || !(b_ray > 0)) return 0;
    // Half the whole path (the mirrored leg to a footprint edge and back directly) at each edge.
    auto half_path = [&](float leg_m, const Angle& aa, const Angle& ee) {
        const glm::dvec3 q = image.origin + double(leg_m) * image.dir(aa, ee);
        return float(0.5 * (leg_m + glm::length(q - f_.origin)));
    };
    Cell& m = g.cell;
    m.range_m = float(0.5 * (hit.t + r1));
    m.range_e_lo_m = half_path(c.range_e_lo_m, a, e_lo), m.range_e_hi_m = half_path(c.range_e_hi_m, a, e_hi);
    m.range_a_lo_m = half_path(c.range_a_lo_m, a_lo, e), m.range_a_hi_m = half_path(c.range_a_hi_m, a_hi, e);
    m.solid_angle_sr = float(c.solid_angle_sr * std::sqrt(b_p / b_ray)); // one way each: sqrt(B_tx B_rx)
    g.other_leg_m = float(r1);
    g.cos_other = float(std::min(1.0, std::abs(glm::dot(hit.normal, v))));
    g.tx_bounces = 0, g.rx_bounces = std::uint8_t(k);
    // The two mixed paths carry the same echo. Out by the mirrors and back directly, it arrives from the
    // scatterer, over the azimuths from which the sonar sees the cell's footprint (its azimuth edges on the
    // scatterer's plane); gather_ghosts() shares it among the beams that interval covers.
    auto azimuth_to = [&](float leg_m, const Angle& aa) {
        const glm::dvec3 w =
            glm::transpose(f_.R) * (image.origin + double(leg_m) * image.dir(aa, e) - f_.origin);
        return std::atan2(w.y, w.x);
    };
    const double z0 = azimuth_to(c.range_a_lo_m, a_lo), z1 = azimuth_to(c.range_a_hi_m, a_hi);
    const double width_rad = std::clamp(std::abs(z1 - z0), 1e-9, 2 * half_azimuth_rad_);
    const double r_lo = range_lo_m(m), r_hi = range_hi_m(m);
    const bool keep_rx = !negligible(g, ray_beam, ray_beam, r_lo, r_hi);
    const bool keep_tx =
        !cull_.echo_db || cull_.echo_db->empty() ||
        !negligible(g, beam_of(a_p + width_rad / 2), beam_of(a_p - width_rad / 2), r_lo, r_hi);
    if (!keep_rx && !keep_tx) return 0; // nor their shadow ray
    std::uint64_t rays = 0;
    if (!blocked || *blocked < 0) {
        const double eps = offset_m(p);
        const bool b = bool(first_hit(g_, s_, p + eps * v, v, r1 - 2 * eps));
        rays = 1;
        if (blocked) *blocked = std::int8_t(b);
        if (b) return rays; // the direct leg is blocked
    } else if (*blocked) {
        return 0;
    }
    // Out directly, back by the mirrors: arrives along the ray.
    g.beam = std::uint32_t(ray_beam);
    if (keep_rx) out.push_back(g);
    g.tx_bounces = std::uint8_t(k), g.rx_bounces = 0;
    m.azimuth_rad = float(a_p), m.elevation_rad = float(e_p);
    m.azimuth_width_rad = float(width_rad);
    // Its footprint's azimuth edges in the interval's order (range_a_lo_m at its lower azimuth, as for a
    // direct cell): gather_ghosts() gives each beam it spans the part of the footprint over its azimuths.
    if (z0 > z1) std::swap(m.range_a_lo_m, m.range_a_hi_m);
    g.beam = std::uint32_t(beam_of(a_p));
    if (keep_tx) out.push_back(g);
    return rays;
}

bool Multipath::negligible(const GhostCell& g, int beam_lo, int beam_hi, double r_lo_m, double r_hi_m) const {
    if (!cull_.echo_db || cull_.echo_db->empty()) return false;
    const int K = s_.sonar.range_bins;
    const SonarGrid& grid = *f_.grid;
    const double b0 = std::max(0.0, std::floor(grid.bin_position(r_lo_m)) - cull_.margin_bins);
    const double b1 = std::min(double(K - 1), std::floor(grid.bin_position(r_hi_m)) + cull_.margin_bins);
    beam_lo = std::max(0, beam_lo - cull_.margin_beams);
    beam_hi = std::min(s_.sonar.beams - 1, beam_hi + cull_.margin_beams);
    if (!(b0 <= b1) || (b1 - b0 + 1) * (beam_hi - beam_lo + 1) > 256) return false; // none, or too many
    // The least floor first (a bin without direct echo: no cull, and no level to evaluate). The ghost's
    // own bin first: most ghosts lie where there is none.
    const float* floor_db = cull_.echo_db->data();
    const auto at = [&](int i, int b) { return floor_db[size_t(i) * size_t(K) + size_t(b)]; };
    float least_db = at((beam_lo + beam_hi) / 2, int(0.5 * (b0 + b1)));
    for (int i = beam_lo; i <= beam_hi && least_db > -INFINITY; ++i)
        for (int b = int(b0); b <= int(b1) && least_db > -INFINITY; ++b)
            least_db = std::min(least_db, at(i, b));
    if (!(least_db > -INFINITY) || !(ghost_echo_db(k_, s_, g) < least_db + cull_.margin_db)) return false;
    culled_.fetch_add(1, std::memory_order_relaxed);
    return true;
}

namespace {
/// A ghost's azimuth interval and the beams it falls in, when it is a mixed path arriving from its
/// scatterer (the only ghosts that may span beams).
struct Span {
    double a0 = 0, a1 = 0; ///< the ghost's azimuth interval [rad]
    int i0 = 0, i1 = 0;    ///< the beams it falls in (i0: the port-most)
};
bool spans_beams(const GhostCell& g, const SonarGrid& grid, Span& span) {
    if (!g.mixed() || g.rx_bounces != 0) return false;
    span.a0 = g.cell.azimuth_rad - 0.5 * g.cell.azimuth_width_rad;
    span.a1 = span.a0 + g.cell.azimuth_width_rad;
    span.i0 = grid.beam_of_azimuth_rad(span.a1), span.i1 = grid.beam_of_azimuth_rad(span.a0);
    return span.i0 != span.i1;
}
} // namespace

bool stays_in_source(const GhostCell& g, std::size_t source, const SonarGrid& grid) {
    Span span;
    return source < std::size_t(grid.beams) && g.beam == source && !spans_beams(g, grid, span);
}

std::vector<std::vector<GhostCell>> gather_ghosts(std::vector<std::vector<GhostCell>>& by_source,
                                                  const SceneDesc& s) {
    const std::shared_ptr<const SonarGrid> grid = sonar_grid(s.sonar);
    // Most ghosts arrive wholly in the beam whose list found them (the double path and the mixed path back
    // by the mirrors arrive along their ray): they stay in that list, in order, which becomes the beam's.
    // The others move to `away` and are appended to their arrival beams' lists after those, by source.
    std::vector<std::vector<GhostCell>> away(by_source.size());
    tbb::parallel_for(size_t(0), by_source.size(), [&](size_t src) {
        auto& v = by_source[src];
        size_t kept = 0;
        for (size_t k = 0; k < v.size(); ++k) {
            if (stays_in_source(v[k], src, *grid)) {
                if (kept != k) v[kept] = v[k];
                ++kept;
            } else {
                away[src].push_back(v[k]);
            }
        }
        v.resize(kept);
    });
    return gather_ghosts(by_source, away, s);
}

std::vector<std::vector<GhostCell>> gather_ghosts(std::vector<std::vector<GhostCell>>& by_source,
                                                  std::vector<std::vector<GhostCell>>& away,
                                                  const SceneDesc& s) {
    const std::shared_ptr<const SonarGrid> grid = sonar_grid(s.sonar);
    const size_t S = by_source.size(), B = size_t(grid->beams);
    std::vector<std::vector<GhostCell>> out(B);
    // A ghost whose azimuth interval spans beams goes to each, with the share of its solid angle that
    // falls in it (the mixed path that arrives from the scatterer); the others lie in beam g.beam.
    auto for_each_share = [&](const GhostCell& g, auto&& add) {
        Span span;
        if (!spans_beams(g, *grid, span)) return add(int(g.beam), g, 1.0);
        for (int i = span.i0; i <= span.i1; ++i) {
            const double hi = grid->beam_port_edge_rad(i), lo = hi - grid->beam_width_rad(i);
            const double f = (std::min(span.a1, hi) - std::max(span.a0, lo)) / g.cell.azimuth_width_rad;
            if (f > 0) add(i, g, f);
        }
    };
    // The moving ghosts' shares, counted per source and arrival beam, then written in parallel over the
    // sources, each at its offset in the arrival beams' lists (sources in order: the same lists as one
    // thread would make).
    std::vector<size_t> at(S * B, 0); // [source * beams + arrival beam]: first count, then offset
    tbb::parallel_for(size_t(0), S, [&](size_t src) {
        for (const auto& g : away[src])
            for_each_share(g, [&](int i, const GhostCell&, double) { ++at[src * B + size_t(i)]; });
    });
    tbb::parallel_for(size_t(0), B, [&](size_t i) {
        if (i < S) out[i] = std::move(by_source[i]);
        size_t n = out[i].size();
        for (size_t src = 0; src < S; ++src) {
            const size_t c = at[src * B + i];
            at[src * B + i] = n, n += c;
        }
        out[i].resize(n);
    });
    tbb::parallel_for(size_t(0), S, [&](size_t src) {
        for (const auto& g : away[src])
            for_each_share(g, [&](int i, const GhostCell& whole, double f) {
                GhostCell& part = out[size_t(i)][at[src * B + size_t(i)]++];
                part = whole;
                if (f < 1) {
                    const double hi = grid->beam_port_edge_rad(i), lo = hi - grid->beam_width_rad(i);
                    const double a0 =
                        std::max(lo, double(whole.cell.azimuth_rad) - 0.5 * whole.cell.azimuth_width_rad);
                    const double a1 =
                        std::min(hi, double(whole.cell.azimuth_rad) + 0.5 * whole.cell.azimuth_width_rad);
                    part.cell.azimuth_rad = float(0.5 * (a0 + a1)),
                    part.cell.azimuth_width_rad = float(a1 - a0);
                    // The range footprint over this part's azimuths only (linear across the interval):
                    // the whole footprint in each beam would smear the ghost's edges by a beam's width.
                    const double w = whole.cell.azimuth_width_rad,
                                 z_lo = double(whole.cell.azimuth_rad) - 0.5 * w;
                    const double r_lo = whole.cell.range_a_lo_m, r_hi = whole.cell.range_a_hi_m;
                    part.cell.range_a_lo_m = float(r_lo + (a0 - z_lo) / w * (r_hi - r_lo));
                    part.cell.range_a_hi_m = float(r_lo + (a1 - z_lo) / w * (r_hi - r_lo));
                    part.cell.solid_angle_sr = float(whole.cell.solid_angle_sr * f);
                }
                part.beam = std::uint32_t(i);
            });
        std::vector<GhostCell>().swap(away[src]);
    });
    for (size_t src = B; src < S; ++src) std::vector<GhostCell>().swap(by_source[src]);
    return out;
}

} // namespace sonarsim::detail

#include "trace.hpp"

#include "pose.hpp"

#include <chrono>
#include <cmath>
#include <tbb/parallel_for.h>

namespace sonarsim {
namespace {

/// A sonar-frame angle and its sine and cosine.
struct Angle {
    double rad, c, s;
    explicit Angle(double r = 0) : rad(r), c(std::cos(r)), s(std::sin(r)) {}
};

glm::dvec3 dir(const glm::dmat3& R, const Angle& a, const Angle& e) {
    return R * glm::dvec3(e.c * a.c, e.c * a.s, e.s);
}

struct RayHit {
    bool hit = false;
    Hit h;
};

/// First hit of one ray against meshes and floor; meshes are skipped when the ray misses their bounds.
RayHit first_hit(const SceneGeometry& g, const SceneDesc& s, const glm::dvec3& o, const glm::dvec3& d,
                 double t_max) {
    RayHit out;
    if (s.seafloor)
        if (auto f = intersect_floor(*s.seafloor, o, d, t_max)) out.hit = true, out.h = *f, t_max = f->t;
    if (g.has_meshes()) {
        // Slab test against the scene bounds first: most rays of a typical scene only see the floor.
        double t0 = 0, t1 = t_max;
        const glm::dvec3 lo = g.bounds_lo(), hi = g.bounds_hi();
        for (int k = 0; k < 3 && t0 <= t1; ++k) {
            const double inv = 1.0 / d[k];
            double a = (lo[k] - o[k]) * inv, b = (hi[k] - o[k]) * inv;
            if (a > b) std::swap(a, b);
            if (std::isnan(a) || std::isnan(b)) { // parallel to the slab: inside or never
                if (o[k] < lo[k] || o[k] > hi[k]) t0 = 1, t1 = 0;
                continue;
            }
            t0 = std::max(t0, a), t1 = std::min(t1, b);
        }
        if (t0 <= t1)
            if (auto m = g.intersect(o, d, t_max)) out.hit = true, out.h = *m;
    }
    return out;
}

/// Range at which the direction d meets the plane through `p` with normal `n`; `fallback` if it does not.
double plane_range(const glm::dvec3& o, const glm::dvec3& p, const glm::dvec3& n, const glm::dvec3& d,
                   double fallback) {
    const double den = glm::dot(n, d);
    const double t = glm::dot(n, p - o) / den;
    return (den != 0 && t > 0 && std::isfinite(t)) ? t : fallback;
}

} // namespace

double elevation_of_ray_rad(const SceneDesc& s, int j) {
    const double phi = deg2rad(s.sonar.elevation_fov_deg);
    return phi / 2 - (j + 0.5) * phi / s.sampling.elevation_rays;
}

TraceResult trace(const SceneGeometry& g, const SceneDesc& s) {
    const auto t_start = std::chrono::steady_clock::now();
    const int N = s.sonar.beams, K = s.sampling.azimuth_rays, M = s.sampling.elevation_rays;
    const double theta = deg2rad(s.sonar.azimuth_fov_deg), phi = deg2rad(s.sonar.elevation_fov_deg);
    const double da = theta / N / K, de = phi / M;
    // Rays reaching past r_max can still spread part of their cell into the window; trace a little beyond.
    const double t_max = s.sonar.range_max_m * 1.05;
    const glm::dmat3 R = rotation_matrix(s.sonar.pose.orientation_deg);
    const glm::dvec3 o = to_glm(s.sonar.pose.position_m);

    // Elevation centres and edges are shared by all beams.
    std::vector<Angle> e_mid(static_cast<size_t>(M)), e_edge(static_cast<size_t>(M) + 1);
    for (int j = 0; j < M; ++j) e_mid[size_t(j)] = Angle(phi / 2 - (j + 0.5) * de);
    for (int j = 0; j <= M; ++j) e_edge[size_t(j)] = Angle(phi / 2 - j * de);

    // Paper normals need each ray's neighbours across beams, so they need the full grid first.
    const bool paper = s.sampling.normals == NormalSource::Paper;
    const int cols = N * K;
    std::vector<glm::vec3> grid_point(paper ? size_t(cols) * M : 0);
    std::vector<char> grid_hit(paper ? size_t(cols) * M : 0, 0);

    TraceResult out;
    out.beams = N;
    out.cells.resize(size_t(N));
    tbb::parallel_for(0, N, [&](int i) {
        auto& cells = out.cells[size_t(i)];
        const double a_beam = theta / 2 - (i + 0.5) * theta / N;
        for (int k = 0; k < K; ++k) {
            const double a_c = a_beam + theta / N / 2 - (k + 0.5) * da;
            const Angle a(a_c), a_lo(a_c - da / 2), a_hi(a_c + da / 2);
            for (int j = 0; j < M; ++j) {
                const Angle& e = e_mid[size_t(j)];
                const glm::dvec3 d = dir(R, a, e);
                const RayHit rh = first_hit(g, s, o, d, t_max);
                if (!rh.hit) continue;
                const glm::dvec3 p = o + rh.h.t * d;
                if (paper) {
                    const size_t gi = size_t(i * K + k) * M + j;
                    grid_point[gi] = glm::vec3(p), grid_hit[gi] = 1;
                }
                Cell c;
                c.point = glm::vec3(p);
                c.range_m = float(rh.h.t);
                c.cos_incidence = float(std::abs(glm::dot(rh.h.normal, d)));
                c.solid_angle_sr = float(e.c * de * da);
                const double r = rh.h.t;
                const double re0 = plane_range(o, p, rh.h.normal, dir(R, a, e_edge[size_t(j) + 1]), -1);
                const double re1 = plane_range(o, p, rh.h.normal, dir(R, a, e_edge[size_t(j)]), -1);
                const double ra0 = plane_range(o, p, rh.h.normal, dir(R, a_lo, e), -1);
                const double ra1 = plane_range(o, p, rh.h.normal, dir(R, a_hi, e), -1);
                // An edge that does not meet the plane (beyond the horizon): mirror the other edge about r.
                c.range_e_lo_m = float(re0 > 0 ? re0 : (re1 > 0 ? 2 * r - re1 : r));
                c.range_e_hi_m = float(re1 > 0 ? re1 : (re0 > 0 ? 2 * r - re0 : r));
                c.range_a_lo_m = float(ra0 > 0 ? ra0 : (ra1 > 0 ? 2 * r - ra1 : r));
                c.range_a_hi_m = float(ra1 > 0 ? ra1 : (ra0 > 0 ? 2 * r - ra0 : r));
                c.material = rh.h.material;
                c.elevation_index = std::uint32_t(k * M + j);
                cells.push_back(c);
            }
        }
    });
    out.rays_traced = std::uint64_t(N) * K * M;

    if (paper) {
        // Paper eq. 13-14: n = (p[i-1,j] - p[i,j]) x (p[i,j-1] - p[i,j]) over the ray grid (column = beam x
        // azimuth sub-ray). Missing neighbours use the other side; with none, the true normal stays.
        tbb::parallel_for(0, N, [&](int i) {
            for (auto& c : out.cells[size_t(i)]) {
                const int k = int(c.elevation_index) / M, j = int(c.elevation_index) % M;
                const int col = i * K + k;
                auto at = [&](int cc, int jj) -> const glm::vec3* {
                    if (cc < 0 || cc >= cols || jj < 0 || jj >= M) return nullptr;
                    const size_t gi = size_t(cc) * M + jj;
                    return grid_hit[gi] ? &grid_point[gi] : nullptr;
                };
                const glm::vec3* pa = at(col - 1, j);
                if (!pa) pa = at(col + 1, j);
                const glm::vec3* pe = at(col, j - 1);
                if (!pe) pe = at(col, j + 1);
                if (!pa || !pe) continue;
                const glm::dvec3 n = glm::cross(glm::dvec3(*pa - c.point), glm::dvec3(*pe - c.point));
                const glm::dvec3 ray = glm::dvec3(c.point) - o;
                const double len = glm::length(n) * glm::length(ray);
                if (len > 0) c.cos_incidence = float(std::abs(glm::dot(n, ray)) / len);
            }
        });
    }
    out.trace_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t_start).count();
    return out;
}

} // namespace sonarsim

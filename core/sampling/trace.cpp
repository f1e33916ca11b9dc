#include "core/sampling/trace.hpp"

#include "core/sampling/acquisition.hpp"
#include "core/sampling/adaptive_sampler.hpp"
#include "core/sampling/motion_trace.hpp"

#include "core/sampling/multipath.hpp"
#include "core/base/timing.hpp"
#include "core/sampling/trace_detail.hpp"

#include <chrono>
#include <cmath>
#include <tbb/parallel_for.h>

namespace sonarsim {

using detail::Angle;

namespace {

/// Paper eq. 13-14: n = (p[c-1,j] - p[c,j]) x (p[c,j-1] - p[c,j]) over the ray grid (column c = beam x
/// azimuth sub-ray). A missing neighbour is replaced by the one on the other side; with none, the true normal
/// stays.
void apply_paper_normals(TraceResult& out, const SceneDesc& s, const std::vector<glm::vec3>& grid_point,
                         const std::vector<char>& grid_hit) {
    const int N = s.sonar.beams, K = s.sampling.azimuth_rays, M = s.sampling.elevation_rays, cols = N * K;
    tbb::parallel_for(0, N, [&](int i) {
        for (auto& c : out.cells[size_t(i)]) {
            const int k = int(c.elevation_index) / M, j = int(c.elevation_index) % M, col = i * K + k;
            auto at = [&](int cc, int jj) -> const glm::vec3* {
                if (cc < 0 || cc >= cols || jj < 0 || jj >= M) return nullptr;
                const size_t gi = size_t(cc) * M + size_t(jj);
                return grid_hit[gi] ? &grid_point[gi] : nullptr;
            };
            const glm::vec3* pa = at(col - 1, j);
            if (!pa) pa = at(col + 1, j);
            const glm::vec3* pe = at(col, j - 1);
            if (!pe) pe = at(col, j + 1);
            if (!pa || !pe) continue;
            // Grid points are stored relative to the sonar, so they keep their precision far from the origin.
            const glm::dvec3 ray(*at(col, j));
            const glm::dvec3 n = glm::cross(glm::dvec3(*pa) - ray, glm::dvec3(*pe) - ray);
            const double len = glm::length(n) * glm::length(ray);
            if (len > 0) c.cos_incidence = float(std::abs(glm::dot(n, ray)) / len);
        }
    });
}

} // namespace

TraceResult trace_uniform(const SceneGeometry& g, const SceneDesc& s, const TraceControl& control) {
    const int N = s.sonar.beams, K = s.sampling.azimuth_rays, M = s.sampling.elevation_rays;
    const detail::RayFrame frame(s);
    const SonarGrid& grid = *frame.grid;
    const double phi = frame.elevation_weight.traced_fov_rad();

    // Elevation centres and edges are shared by all beams.
    const std::vector<Angle> e_mid = detail::even_angles(phi, M, true), e_edge = detail::even_angles(phi, M);

    // Paper normals need each ray's neighbours across beams, so they need the full grid first (hit points
    // relative to the sonar).
    const bool paper = s.sampling.normals == NormalSource::Paper;
    std::vector<glm::vec3> grid_point(paper ? size_t(N) * K * M : 0);
    std::vector<char> grid_hit(paper ? size_t(N) * K * M : 0, 0);

    TraceResult out;
    out.beams = N;
    out.cells.resize(size_t(N));
    const bool multipath = detail::multipath_active(s);
    const detail::Multipath mp(g, s, frame);
    std::vector<std::vector<GhostCell>> ghosts(multipath ? size_t(N) : 0);
    std::vector<std::uint64_t> ghost_rays(static_cast<size_t>(N), 0);
    tbb::parallel_for(0, N, [&](int i) {
        if (control.cancelled() || !control.traces(i)) return;
        auto& cells = out.cells[size_t(i)];
        const double a_beam_lo = grid.beam_starboard_edge_rad(i), da = grid.beam_width_rad(i) / K;
        for (int k = 0; k < K; ++k) {
            const double a_c = a_beam_lo + (K - k - 0.5) * da; // sub-ray 0 is the port-most
            const Angle a(a_c), a_lo(a_c - da / 2), a_hi(a_c + da / 2);
            for (int j = 0; j < M; ++j) {
                const glm::dvec3 d = frame.dir(a, e_mid[size_t(j)]);
                const auto h = detail::first_hit(g, s, frame.origin, d, frame.t_max);
                if (!h) continue;
                Cell c = detail::make_cell(frame, *h, a, e_mid[size_t(j)], a_lo, a_hi, e_edge[size_t(j) + 1],
                                           e_edge[size_t(j)]);
                c.elevation_index = std::uint32_t(k * M + j);
                if (multipath)
                    ghost_rays[size_t(i)] +=
                        mp.ghosts(*h, a, e_mid[size_t(j)], a_lo, a_hi, e_edge[size_t(j) + 1],
                                  e_edge[size_t(j)], i, ghosts[size_t(i)]);
                if (paper) {
                    const size_t gi = size_t(i * K + k) * M + size_t(j);
                    grid_point[gi] = glm::vec3(h->t * d), grid_hit[gi] = 1; // p - o
                }
                cells.push_back(c);
            }
        }
    });
    if (control.cancelled()) throw TraceCancelled();
    out.rays_traced = std::uint64_t(control.traced_beams(N)) * K * M;
    if (multipath) {
        out.ghosts = detail::gather_ghosts(ghosts, s);
        for (auto r : ghost_rays) out.multipath_rays += r;
    }
    if (paper) apply_paper_normals(out, s, grid_point, grid_hit);
    return out;
}

TraceResult trace(const SceneGeometry& g, const SceneDesc& s, const TraceControl& control, ImagePass* pass) {
    const auto t0 = std::chrono::steady_clock::now();
    if (pass) pass->forget(); // it holds no pass of these hits unless the tracer runs one
    TraceResult out;
    if (moving(s.sonar)) {
        out = trace_moving(g, s, control);
    } else {
        switch (s.sampling.placement) { // one case per row of kRayPlacements
        case RayPlacement::Grid:
            out = trace_uniform(g, s, control);
            break;
        case RayPlacement::Adaptive:
            out = trace_adaptive(g, s, control, pass);
            break;
        case RayPlacement::Jittered:
            out = trace_jittered(g, s, control);
            break;
        }
    }
    out.trace_ms = ms_since(t0);
    return out;
}

std::size_t hits_bytes(const TraceResult& t) {
    std::size_t n = sizeof(TraceResult);
    for (const auto& b : t.cells) n += b.capacity() * sizeof(Cell);
    for (const auto& b : t.ghosts) n += b.capacity() * sizeof(GhostCell);
    for (const auto& b : t.stratum_cells) n += b.capacity() * sizeof(Cell);
    if (const AdaptiveEstimateCells* k = t.estimate_cells.get())
        for (const TraceResult* r : {&k->coarse, &k->coarse_edges, &k->az_one, &k->az_three})
            n += hits_bytes(*r);
    return n;
}

} // namespace sonarsim

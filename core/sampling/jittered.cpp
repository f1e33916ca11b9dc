// Jittered placement: a beam's azimuth_rays x elevation_rays strata (of its width and of the traced
// aperture) hold four rays each: two antithetic pairs (a point drawn uniformly in the stratum by a seeded
// hash, and its mirror about the stratum's centre), the pairs independent. Each pair is an estimate of the
// image that is second order on a smooth surface, as the midpoint rule is; the two pairs (Cell::half) are
// independent estimates, whose difference measures the sampling error (shading/estimate.hpp). A pair's two
// rays fall in opposite halves of the stratum in elevation, and each ray's cell is its half. The same scene
// always traces the same rays.
#include "core/sampling/trace.hpp"

#include "core/sampling/multipath.hpp"
#include "core/sampling/trace_detail.hpp"

#include <algorithm>
#include <cstdint>
#include <tbb/parallel_for.h>

namespace sonarsim {

namespace {

using detail::Angle;

/// About this many beams of an image carry the estimate's whole-stratum cells (every stride-th traced beam).
constexpr int kEstimateBeams = 32;

constexpr std::uint64_t mix(std::uint64_t x) { // splitmix64's finaliser
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

/// Two uniforms in [0, 1) for pair `half` of stratum (column k, row j) of beam i.
std::pair<double, double> jitter(int i, int k, int j, int half) {
    const std::uint64_t key =
        mix(mix(mix(std::uint64_t(i) + 0x51ull) ^ std::uint64_t(k)) ^ std::uint64_t(j)) ^ std::uint64_t(half);
    const std::uint64_t a = mix(key), b = mix(a);
    return {double(a >> 11) * 0x1.0p-53, double(b >> 11) * 0x1.0p-53};
}

} // namespace

TraceResult trace_jittered(const SceneGeometry& g, const SceneDesc& s, const TraceControl& control) {
    const int N = s.sonar.beams, K = s.sampling.azimuth_rays, M = s.sampling.elevation_rays;
    const detail::RayFrame frame(s);
    const SonarGrid& grid = *frame.grid;
    const double phi = frame.elevation_weight.traced_fov_rad(), de = phi / M;
    const std::vector<Angle> e_edge = detail::even_angles(phi, M), e_mid = detail::even_angles(phi, M, true);

    TraceResult out;
    out.beams = N;
    out.cells.resize(size_t(N));
    out.halves = true;
    const bool multipath = detail::multipath_active(s);
    const detail::Multipath mp(g, s, frame);
    std::vector<std::vector<GhostCell>> ghosts(multipath ? size_t(N) : 0);
    std::vector<std::uint64_t> ghost_rays(static_cast<size_t>(N), 0);
    // The beams whose rays also make cells of their whole stratum (the footprint's bias, estimate_error).
    const int stride = std::max(1, control.traced_beams(N) / kEstimateBeams);
    out.stratum_cells.resize(size_t(N));
    std::vector<char> sampled(static_cast<size_t>(N), 0);
    for (int i = 0, seen = 0; i < N; ++i)
        if (control.traces(i)) sampled[size_t(i)] = seen++ % stride == 0;
    // Each ray's cell: the half of its stratum (in elevation) it falls in; the antithetic pair's two rays
    // fall in opposite halves. Edges of the halves, and their centres.
    const std::vector<Angle> e_sub_edge = detail::even_angles(phi, 2 * M),
                             e_sub_mid = detail::even_angles(phi, 2 * M, true);
    tbb::parallel_for(0, N, [&](int i) {
        if (control.cancelled() || !control.traces(i)) return;
        auto& cells = out.cells[size_t(i)];
        cells.reserve(size_t(4) * K * M);
        std::vector<std::pair<Angle, Angle>> centre(static_cast<size_t>(M)), sub_centre(size_t(2) * M);
        auto* whole = sampled[size_t(i)] ? &out.stratum_cells[size_t(i)] : nullptr;
        if (whole) whole->reserve(size_t(4) * K * M);
        const double a_beam_lo = grid.beam_starboard_edge_rad(i), da = grid.beam_width_rad(i) / K;
        for (int k = 0; k < K; ++k) {
            const double a_lo_rad = a_beam_lo + (K - k - 1) * da; // column 0 is the port-most
            const Angle a_lo(a_lo_rad), a_hi(a_lo_rad + da), a_c(a_lo_rad + da / 2);
            for (int j = 0; j < M; ++j) centre[size_t(j)] = {a_c, e_mid[size_t(j)]};
            for (int j = 0; j < 2 * M; ++j) sub_centre[size_t(j)] = {a_c, e_sub_mid[size_t(j)]};
            for (int j = 0; j < M; ++j) {
                for (int ray = 0; ray < 4; ++ray) {
                    const int half = ray >> 1;
                    auto [ua, ue] = jitter(i, k, j, half);
                    if (ray & 1) ua = 1 - ua, ue = 1 - ue;
                    const Angle a(a_lo_rad + ua * da), e(e_edge[size_t(j)].rad - ue * de);
                    const glm::dvec3 d = frame.dir(a, e);
                    const auto h = detail::first_hit(g, s, frame.origin, d, frame.t_max);
                    if (!h) continue;
                    const int sub = 2 * j + (ue < 0.5 ? 0 : 1); // top half first
                    Cell c = detail::make_cell(frame, *h, a, e, a_lo, a_hi, e_sub_edge[size_t(sub) + 1],
                                               e_sub_edge[size_t(sub)], &sub_centre[size_t(sub)]);
                    c.solid_angle_sr *= 0.5f; // each half of the stratum holds one ray of each pair
                    c.azimuth_rad = float(a_lo_rad + da / 2); // the stratum's centre: its azimuth extent
                    c.elevation_index = std::uint32_t(k * M + j);
                    c.half = std::uint8_t(half);
                    if (multipath) {
                        auto& gs = ghosts[size_t(i)];
                        const size_t before = gs.size();
                        ghost_rays[size_t(i)] +=
                            mp.ghosts(*h, a, e, a_lo, a_hi, e_edge[size_t(j) + 1], e_edge[size_t(j)], i, gs);
                        for (size_t n = before; n < gs.size(); ++n)
                            gs[n].cell.solid_angle_sr *= 0.25f, gs[n].cell.half = std::uint8_t(half);
                    }
                    cells.push_back(c);
                    if (whole) { // the same ray with the whole stratum as its cell
                        Cell m = detail::make_cell(frame, *h, a, e, a_lo, a_hi, e_edge[size_t(j) + 1],
                                                   e_edge[size_t(j)], &centre[size_t(j)]);
                        m.solid_angle_sr *= 0.25f, m.azimuth_rad = c.azimuth_rad, m.half = c.half;
                        whole->push_back(m);
                    }
                }
            }
        }
    });
    if (control.cancelled()) throw TraceCancelled();
    out.rays_traced = std::uint64_t(control.traced_beams(N)) * K * M * 4;
    if (multipath) {
        out.ghosts = detail::gather_ghosts(ghosts, s);
        for (auto r : ghost_rays) out.multipath_rays += r;
    }
    return out;
}

} // namespace sonarsim

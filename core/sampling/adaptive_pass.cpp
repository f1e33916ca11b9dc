// Adaptive sampling: one pass at a given base grid (trace, refine, cells, error estimate).
#include "core/sampling/adaptive_sampler.hpp"

#include "core/analysis/reference.hpp"
#include "core/shading/accumulate.hpp"

#include <tbb/parallel_for.h>

#include <array>
#include <cmath>
#include <limits>

namespace sonarsim::adaptive {
namespace {

/// Azimuth centre of column k of K in beam i (column 0 is the port-most).
double column_azimuth(const SonarGrid& grid, int i, int k, int K) {
    return grid.beam_port_edge_rad(i) - (k + 0.5) * grid.beam_width_rad(i) / K;
}

/// The base grid: azimuth_rays columns of M0 cells per beam, sibling triples grouped.
Beams trace_base_grid(const Sampler& sp, int M0) {
    const SceneDesc& s = sp.s;
    const SonarGrid& grid = *sp.frame.grid;
    const int N = grid.beams, K0 = s.sampling.azimuth_rays;
    Beams beams(static_cast<size_t>(N));
    sp.rays.fetch_add(std::uint64_t(sp.base_rays(M0))); // the base grid is always traced
    tbb::parallel_for(0, N, [&](int i) {
        if (!sp.control.traces(i)) return; // left without columns, so without cells
        for (int k = 0; k < K0; ++k) {
            beams[size_t(i)].push_back(
                sp.trace_column(column_azimuth(grid, i, k, K0), grid.beam_width_rad(i) / K0, M0, i, 0, M0));
            beams[size_t(i)].back().group = k / 3 + (K0 % 3 && k >= K0 - K0 % 3 ? K0 + k : 0);
        }
    });
    return beams;
}

/// The base grid's echo per bin of one beam, for the criteria's significance test: each cell's echo spread
/// evenly over its range footprint (a cheap stand-in for shading the base cells), summed relative to the
/// beam's peak; written to out[0, range_bins).
void base_echo(const SceneDesc& s, double bin_m, const std::vector<Column>& cols, float* out) {
    const int K = s.sonar.range_bins;
    double peak = -std::numeric_limits<double>::infinity();
    for (const auto& c : cols)
        for (const auto& n : c.nodes)
            if (n.hit) peak = std::max(peak, n.density_db); // a scale only: cells are below 1 sr
    if (!std::isfinite(peak)) return;
    std::vector<double> lin(static_cast<size_t>(K), 0.0);
    for (const auto& c : cols)
        for (const auto& n : c.nodes) {
            if (!n.hit) continue;
            const double e = std::exp(kLn10Over10 * (n.density_db - peak)) * n.angle.c * n.de * c.da;
            const double r0 = n.hit->t - 0.5 * n.footprint_m, r1 = n.hit->t + 0.5 * n.footprint_m;
            const double b0 = std::floor((r0 - s.sonar.range_min_m) / bin_m);
            const double b1 = std::floor((r1 - s.sonar.range_min_m) / bin_m);
            if (b1 < 0 || b0 >= K) continue;
            const int lo = int(std::max(0.0, b0)), hi = int(std::min(double(K - 1), b1));
            const double share = e / (hi - lo + 1);
            for (int b = lo; b <= hi; ++b) lin[size_t(b)] += share;
        }
    for (int b = 0; b < K; ++b)
        if (lin[size_t(b)] > 0) out[b] = float(peak + 10 * std::log10(lin[size_t(b)]));
}

/// The base grid's image sets the scale of what is worth refining (none when nothing is refined).
void set_base_image(Sampler& sp, const Beams& beams) {
    const SceneDesc& s = sp.s;
    const int N = s.sonar.beams, K = s.sonar.range_bins;
    auto& base_db = sp.criteria.base_db;
    base_db.clear();
    if (sp.elevation_levels == 0 && sp.azimuth_levels == 0) return;
    base_db.assign(size_t(N) * size_t(K), -std::numeric_limits<float>::infinity());
    tbb::parallel_for(0, N, [&](int i) {
        base_echo(s, sp.criteria.bin_m(), beams[size_t(i)], base_db.data() + size_t(i) * size_t(K));
    });
}

/// The cells of the refined columns (fine) and, on the `sampled` beams unless previewing, the same cells
/// one level coarser: sibling column triples -> the middle column (3 da), and within each column sibling
/// elevation triples -> the middle cell. Frees the columns.
void collect_cells(const Sampler& sp, Beams& beams, const std::vector<int>& sampled_beams, TraceResult& fine,
                   TraceResult& coarse) {
    const SceneDesc& s = sp.s;
    const int N = s.sonar.beams, sampled = int(sampled_beams.size());
    std::vector<int> slot(static_cast<size_t>(N), -1); // beam -> its place among the sampled
    for (int k = 0; k < sampled; ++k) slot[size_t(sampled_beams[size_t(k)])] = k;
    fine.beams = N, coarse.beams = sampled;
    coarse.cells.resize(size_t(sampled)), fine.cells.resize(size_t(N));
    std::vector<std::vector<GhostCell>> fine_ghosts(static_cast<size_t>(N)),
        coarse_ghosts(static_cast<size_t>(sampled));
    std::vector<std::uint64_t> ghost_rays(static_cast<size_t>(N), 0);
    tbb::parallel_for(0, N, [&](int i) {
        const auto& cols = beams[size_t(i)];
        size_t nodes = 0;
        for (auto& c : cols) nodes += c.nodes.size();
        fine.cells[size_t(i)].reserve(nodes);
        for (auto& c : cols)
            ghost_rays[size_t(i)] +=
                sp.cells_of(c, false, c.da, fine.cells[size_t(i)], fine_ghosts[size_t(i)]);
        if (sp.control.preview || slot[size_t(i)] < 0) return;
        auto& coarse_cells = coarse.cells[size_t(slot[size_t(i)])];
        auto& coarse_ghost = coarse_ghosts[size_t(slot[size_t(i)])];
        for (size_t k = 0; k < cols.size();) {
            if (k + 2 < cols.size() && cols[k].group == cols[k + 1].group &&
                cols[k].group == cols[k + 2].group) {
                ghost_rays[size_t(i)] +=
                    sp.cells_of(cols[k + 1], true, 3 * cols[k + 1].da, coarse_cells, coarse_ghost);
                k += 3;
            } else {
                ghost_rays[size_t(i)] += sp.cells_of(cols[k], true, cols[k].da, coarse_cells, coarse_ghost);
                ++k;
            }
        }
    });
    if (sp.multipath) {
        fine.ghosts = detail::gather_ghosts(fine_ghosts, s);
        coarse.ghosts = detail::gather_ghosts(coarse_ghosts, s);
        for (auto r : ghost_rays) fine.multipath_rays += r;
    }
    for (auto& b : beams)
        for (auto& c : b) fine.rays_traced += c.rays;
    beams.clear(); // the nodes are no longer needed: free them before shading
    beams.shrink_to_fit();
}

/// The scene of `sampled` of its beams as an image of their own (shade() sums beam by beam, so a beam's image
/// does not depend on the others; the image channel needs no beam angles, so they are even).
SceneDesc sampled_beams_scene(const SceneDesc& s, int sampled) {
    SceneDesc out = s;
    out.sonar.beams = sampled;
    out.sonar.beam_table = kUniformBeams;
    return out;
}

/// The error of the fine image, estimated from its difference to the coarse cells' image on the sampled
/// beams (every stride-th).
TraceResult::ErrorEstimate estimate_error(const SceneDesc& s, const PolarImage& fine_image,
                                          const TraceResult& coarse, const std::vector<int>& sampled_beams) {
    const int sampled = coarse.beams;
    const SceneDesc sampled_scene = sampled_beams_scene(s, sampled);
    PolarImage fine_sampled;
    fine_sampled.bins = fine_image.bins, fine_sampled.beams = sampled;
    fine_sampled.level_db.resize(size_t(fine_image.bins) * size_t(sampled));
    for (int b = 0; b < fine_image.bins; ++b)
        for (int i = 0; i < sampled; ++i)
            fine_sampled.level_db[size_t(b) * size_t(sampled) + size_t(i)] =
                fine_image.at(b, sampled_beams[size_t(i)]);
    const ImageError e = compare_images(shade(coarse, sampled_scene), fine_sampled);
    // The coarse image's error is taken as three times the fine one's (first order at discontinuities, the
    // slowest case): fine error ~ |fine - coarse| / 2.
    TraceResult::ErrorEstimate est;
    est.valid = true;
    est.rel_l1 = e.rel_l1 / 2, est.median_abs_db = e.median_abs_db / 2, est.p95_abs_db = e.p95_abs_db / 2;
    return est;
}

} // namespace

std::uint64_t Sampler::cells_of(const Column& c, bool coarse, double da, std::vector<Cell>& out,
                                std::vector<GhostCell>& ghosts) const {
    std::uint64_t rays = 0;
    const Angle a(c.a), a_lo(c.a - da / 2), a_hi(c.a + da / 2);
    // Cell widths come in a few sizes (de0 / 3^k): keep sin and cos of their halves.
    std::array<std::pair<double, Angle>, 12> halves{};
    size_t n_halves = 0;
    auto half = [&](double de) -> const Angle& {
        for (size_t k = 0; k < n_halves; ++k)
            if (halves[k].first == de) return halves[k].second;
        auto& slot = halves[std::min(n_halves, halves.size() - 1)];
        n_halves = std::min(n_halves + 1, halves.size());
        slot = {de, Angle(de / 2)};
        return slot.second;
    };
    auto emit = [&](const Node& n, double de) {
        if (!n.hit) return;
        const Angle& h = half(de);
        const Angle& e = n.angle;
        Angle lo, hi; // e -+ de/2 by the angle-sum identities
        lo.rad = e.rad - h.rad, lo.c = e.c * h.c + e.s * h.s, lo.s = e.s * h.c - e.c * h.s;
        hi.rad = e.rad + h.rad, hi.c = e.c * h.c - e.s * h.s, hi.s = e.s * h.c + e.c * h.s;
        out.push_back(detail::make_cell(frame, *n.hit, a, e, a_lo, a_hi, lo, hi));
        if (multipath) rays += mp.ghosts(*n.hit, a, e, a_lo, a_hi, lo, hi, ghosts, n.via);
    };
    for (size_t n = 0; n < c.nodes.size();) {
        if (coarse && n + 2 < c.nodes.size() && c.nodes[n].group == c.nodes[n + 1].group &&
            c.nodes[n].group == c.nodes[n + 2].group) {
            emit(c.nodes[n + 1], 3 * c.nodes[n + 1].de);
            n += 3;
        } else {
            emit(c.nodes[n], c.nodes[n].de);
            ++n;
        }
    }
    return rays;
}

/// The base grid's own error, estimated as the refined image's is (against its sibling triples merged, on
/// every stride-th beam): the error that refinement, which works only at discontinuities, starts from.
TraceResult::ErrorEstimate base_error(const Sampler& sp, const Beams& beams,
                                      const std::vector<int>& sampled_beams) {
    const SceneDesc& s = sp.s;
    const int sampled = int(sampled_beams.size());
    TraceResult fine, coarse;
    fine.beams = coarse.beams = sampled;
    fine.cells.resize(size_t(sampled)), coarse.cells.resize(size_t(sampled));
    tbb::parallel_for(0, sampled, [&](int k) {
        std::vector<GhostCell> ghosts; // base_error is not used with multipath
        for (const auto& c : beams[size_t(sampled_beams[size_t(k)])]) {
            sp.cells_of(c, false, c.da, fine.cells[size_t(k)], ghosts);
            sp.cells_of(c, true, c.da, coarse.cells[size_t(k)], ghosts);
        }
    });
    const SceneDesc sampled_scene = sampled_beams_scene(s, sampled);
    const ImageError e = compare_images(shade(coarse, sampled_scene), shade(fine, sampled_scene));
    TraceResult::ErrorEstimate est;
    est.valid = true;
    est.rel_l1 = e.rel_l1 / 2, est.median_abs_db = e.median_abs_db / 2, est.p95_abs_db = e.p95_abs_db / 2;
    return est;
}

TraceResult trace_pass(Sampler& sp, int M0, TraceResult::ErrorEstimate& est, bool may_skip, bool& skipped) {
    skipped = false;
    const SceneDesc& s = sp.s;
    const int N = s.sonar.beams, traced = int(sp.traced.size());
    sp.set_base_grid(M0);
    Beams beams = trace_base_grid(sp, M0);
    // A base grid whose own error is kSkipFactor x the tolerance or more is left unrefined when a denser
    // one follows: refinement fixes edges, not the error of every smooth cell, and the denser grid's
    // refinement would redo it.
    if (may_skip && !sp.control.preview && !sp.multipath && M0 >= 9) {
        const int stride = traced >= 8 * kEstimateStride ? kEstimateStride : 1;
        const TraceResult::ErrorEstimate base = base_error(sp, beams, sp.sampled_beams(stride));
        if (base.rel_l1 > kSkipFactor * s.sampling.tolerance_rel_l1 ||
            base.median_abs_db > kSkipFactor * s.sampling.tolerance_db) {
            est = base;
            skipped = true;
            TraceResult out;
            for (auto& b : beams)
                for (auto& c : b) out.rays_traced += c.rays;
            return out;
        }
    }
    set_base_image(sp, beams);
    tbb::parallel_for(0, N, [&](int i) {
        for (auto& c : beams[size_t(i)]) sp.refine_column(c, M0);
    });
    sp.refine_azimuth(beams, M0);
    if (sp.control.cancelled()) throw TraceCancelled();
    // The error estimate compares the image with the same cells one level coarser on every
    // kEstimateStride-th beam (all beams of narrow images): a sample of the image, at a quarter of the cost.
    // With multipath every beam: ghosts arrive in beams other than their rays'.
    const int stride = traced >= 8 * kEstimateStride && !sp.multipath ? kEstimateStride : 1;
    const std::vector<int> sampled = sp.sampled_beams(stride);
    TraceResult fine, coarse;
    collect_cells(sp, beams, sampled, fine, coarse);
    // The accumulation pass on the fine cells: the image the estimate needs, with every channel the caller
    // asked for (TraceControl::channels), so that the caller need not shade these cells again.
    Channels channels = sp.control.channels;
    channels.image = true;
    auto shaded = std::make_shared<const Accumulation>(accumulate(fine, s, channels));
    if (!sp.control.preview) est = estimate_error(s, *shaded->image, coarse, sampled);
    fine.shaded = std::move(shaded);
    fine.preview = sp.control.preview;
    return fine;
}

} // namespace sonarsim::adaptive

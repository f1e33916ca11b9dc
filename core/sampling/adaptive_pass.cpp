// Adaptive sampling: one pass at a given base grid (trace, refine, cells, error estimate).
#include "core/sampling/adaptive_sampler.hpp"

#include "core/analysis/reference.hpp"
#include "core/base/fast_math.hpp"
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

/// The base grid: azimuth_rays columns of M0 cells per beam, sibling triples grouped. A beam with columns
/// in `carried` (its base grid at M0 / 3) keeps their rays: each cell splits in three.
Beams trace_base_grid(const Sampler& sp, int M0, Beams* carried) {
    const SceneDesc& s = sp.s;
    const SonarGrid& grid = *sp.frame.grid;
    const int N = grid.beams, K0 = s.sampling.azimuth_rays;
    Beams beams(static_cast<size_t>(N));
    auto kept = [&](int i) {
        return carried && size_t(i) < carried->size() && !(*carried)[size_t(i)].empty();
    };
    double rays = 0; // the base grid is always traced
    for (int i = 0; i < N; ++i)
        if (sp.traces(i)) rays += kept(i) ? sp.base_rays(M0, 1) * 2 / 3 : sp.base_rays(M0, 1);
    sp.rays.fetch_add(std::uint64_t(rays));
    tbb::parallel_for(0, N, [&](int i) {
        if (!sp.traces(i)) return; // left without columns, so without cells
        if (kept(i)) {
            beams[size_t(i)] = std::move((*carried)[size_t(i)]);
            (*carried)[size_t(i)].clear();
            for (auto& c : beams[size_t(i)]) sp.densify_column(c, M0);
            return;
        }
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
            const double e =
                fast::exp2_nonpositive(kLog2_10Over10 * (n.density_db - peak)) * n.angle.c * n.de * c.da;
            const double r0 = n.hit->t - 0.5 * n.footprint_m, r1 = n.hit->t + 0.5 * n.footprint_m;
            const double b0 = std::floor((r0 - s.sonar.range_min_m) / bin_m);
            const double b1 = std::floor((r1 - s.sonar.range_min_m) / bin_m);
            if (b1 < 0 || b0 >= K) continue;
            const int lo = int(std::max(0.0, b0)), hi = int(std::min(double(K - 1), b1));
            const double share = e / (hi - lo + 1);
            for (int b = lo; b <= hi; ++b) lin[size_t(b)] += share;
        }
    for (int b = 0; b < K; ++b)
        if (lin[size_t(b)] > 0) out[b] = float(peak + kDbPerOctave * fast::log2_positive(lin[size_t(b)]));
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
    double peak = -std::numeric_limits<double>::infinity(), cells = 0;
    for (float v : base_db) peak = std::max(peak, double(v));
    for (const auto& b : beams)
        for (const auto& c : b) cells += double(c.nodes.size());
    sp.criteria.cell_share_db = -std::numeric_limits<double>::infinity();
    if (!std::isfinite(peak) || cells == 0) return;
    double sum = 0;
    for (float v : base_db) sum += fast::exp2_nonpositive(kLog2_10Over10 * (double(v) - peak));
    sp.criteria.cell_share_db =
        peak + 10 * std::log10(kCellShare * s.sampling.tolerance_rel_l1 * sum / cells);
}

/// The cells of the refined columns (fine) and, on the `samples` beams (slot k: samples[k]; -1: none)
/// unless previewing, the same cells one level coarser: sibling column triples -> the middle column
/// (3 da), and within each column sibling elevation triples -> the middle cell. Frees the columns.
void collect_cells(const Sampler& sp, Beams& beams, const std::vector<int>& samples, TraceResult& fine,
                   TraceResult& coarse) {
    const SceneDesc& s = sp.s;
    const int N = s.sonar.beams, sampled = int(samples.size());
    std::vector<int> slot(static_cast<size_t>(N), -1); // beam -> its slot
    for (int k = 0; k < sampled; ++k)
        if (samples[size_t(k)] >= 0) slot[size_t(samples[size_t(k)])] = k;
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
        if (sp.multipath) fine_ghosts[size_t(i)].reserve(3 * nodes); // at most three per cell (bounces 1)
        for (auto& c : cols)
            ghost_rays[size_t(i)] +=
                sp.cells_of(c, false, c.da, fine.cells[size_t(i)], fine_ghosts[size_t(i)]);
        if (sp.control.preview || slot[size_t(i)] < 0) return;
        auto& coarse_cells = coarse.cells[size_t(slot[size_t(i)])];
        auto& coarse_ghost = coarse_ghosts[size_t(slot[size_t(i)])];
        if (sp.multipath) coarse_ghost.reserve(3 * nodes);
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
        if (multipath) rays += mp.ghosts(*n.hit, a, e, a_lo, a_hi, lo, hi, c.beam, ghosts, n.via);
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

/// The base grid's own error on each group's sample beam, estimated as the refined image's is (against
/// its sibling triples merged): the error that refinement, which works only at discontinuities, starts
/// from.
static std::vector<SampleError> base_errors(Sampler& sp, const Beams& beams, const BeamGroups& groups) {
    const SceneDesc& s = sp.s;
    const int sampled = int(groups.size());
    TraceResult fine, coarse;
    fine.beams = coarse.beams = sampled;
    fine.cells.resize(size_t(sampled)), coarse.cells.resize(size_t(sampled));
    tbb::parallel_for(0, sampled, [&](int k) {
        std::vector<GhostCell> ghosts; // not used with multipath
        for (const auto& c : beams[size_t(groups[size_t(k)].front())]) {
            sp.cells_of(c, false, c.da, fine.cells[size_t(k)], ghosts);
            sp.cells_of(c, true, c.da, coarse.cells[size_t(k)], ghosts);
        }
    });
    const SceneDesc sampled_scene = sampled_beams_scene(s, sampled);
    const PolarImage f = shade(fine, sampled_scene);
    sp.set_ref_db(f);
    return sample_errors(shade(coarse, sampled_scene), f, sp.ref_db);
}

PassCells trace_pass(Sampler& sp, int M0, const BeamGroups& groups, const BumpRule* bump, Beams* carried) {
    const SceneDesc& s = sp.s;
    const int N = s.sonar.beams, G = int(groups.size());
    sp.pass_beams.assign(size_t(N), 0);
    for (const auto& grp : groups)
        for (int i : grp) sp.pass_beams[size_t(i)] = 1;
    sp.set_base_grid(M0);
    Beams beams = trace_base_grid(sp, M0, carried);
    PassCells out;
    out.bumped.assign(size_t(G), 0);
    if (bump && !sp.control.preview && !sp.multipath && M0 >= 9) {
        out.bumped = (*bump)(base_errors(sp, beams, groups));
        for (int k = 0; k < G; ++k) {
            if (!out.bumped[size_t(k)]) continue;
            if (carried) carried->resize(size_t(N));
            for (int i : groups[size_t(k)]) {
                // To a denser base grid, unrefined here: `carried` keeps its rays (counted when collected).
                if (carried)
                    (*carried)[size_t(i)] = std::move(beams[size_t(i)]);
                else
                    for (auto& c : beams[size_t(i)]) out.fine.rays_traced += c.rays;
                beams[size_t(i)].clear();
            }
        }
    }
    set_base_image(sp, beams);
    // Ghosts far below the base image's direct echo are culled (multipath.hpp, kGhostCullShare).
    if (sp.multipath)
        sp.mp.set_cull_floor({&sp.criteria.base_db,
                              sp.criteria.tolerance_per_bin_db() + 10 * std::log10(detail::kGhostCullShare),
                              2, 1});
    tbb::parallel_for(0, N, [&](int i) {
        for (auto& c : beams[size_t(i)]) sp.refine_column(c, M0);
    });
    sp.refine_azimuth(beams, M0);
    if (sp.control.cancelled()) throw TraceCancelled();
    std::vector<int> samples(static_cast<size_t>(G), -1);
    for (int k = 0; k < G; ++k)
        if (!out.bumped[size_t(k)]) samples[size_t(k)] = groups[size_t(k)].front();
    collect_cells(sp, beams, samples, out.fine, out.coarse); // adds the refined beams' rays
    out.fine.preview = sp.control.preview;
    return out;
}

} // namespace sonarsim::adaptive

// Adaptive sampling: one pass at a given base grid: the base grid traced, its image and the bump decision,
// refinement, the azimuth probe; the cells come from adaptive_cells.cpp.
#include "core/sampling/adaptive_sampler.hpp"

#include "core/base/fast_math.hpp"
#include "core/shading/accumulate.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
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
    const int N = grid.beams;
    Beams beams(static_cast<size_t>(N));
    auto kept = [&](int i) {
        return carried && size_t(i) < carried->size() && !(*carried)[size_t(i)].empty();
    };
    double rays = 0; // the base grid is always traced
    for (int i = 0; i < N; ++i)
        if (sp.traces(i))
            rays += (kept(i) ? sp.base_rays(M0, 1) * 2 / 3 : sp.base_rays(M0, 1)) *
                    (sp.columns(i) / s.sampling.azimuth_rays);
    sp.rays.fetch_add(std::uint64_t(rays));
    tbb::parallel_for(0, N, [&](int i) {
        if (!sp.traces(i)) return; // left without columns, so without cells
        if (kept(i)) {
            beams[size_t(i)] = std::move((*carried)[size_t(i)]);
            (*carried)[size_t(i)].clear();
            for (auto& c : beams[size_t(i)]) sp.densify_column(c, M0);
            return;
        }
        const int K0 = sp.columns(i);
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
void base_echo(const SceneDesc& s, const SonarGrid& grid, const std::vector<Column>& cols, float* out) {
    const int K = s.sonar.range_bins;
    double peak = -std::numeric_limits<double>::infinity();
    for (const auto& c : cols)
        for (const auto& n : c.nodes)
            if (n.hit) peak = std::max(peak, n.density_db); // a scale only: cells are below 1 sr
    if (!std::isfinite(peak)) return;
    thread_local std::vector<double> lin; // used only within this call
    lin.assign(static_cast<size_t>(K), 0.0);
    for (const auto& c : cols)
        for (const auto& n : c.nodes) {
            if (!n.hit) continue;
            const double e =
                fast::exp2_nonpositive(kLog2_10Over10 * (n.density_db - peak)) * n.angle.c * n.de * c.da;
            const double r0 = n.hit->t - 0.5 * n.footprint_m, r1 = n.hit->t + 0.5 * n.footprint_m;
            const double b0 = std::floor(grid.bin_position(r0)), b1 = std::floor(grid.bin_position(r1));
            if (b1 < 0 || b0 >= K) continue;
            const int lo = int(std::max(0.0, b0)), hi = int(std::min(double(K - 1), b1));
            const double share = e / (hi - lo + 1);
            for (int b = lo; b <= hi; ++b) lin[size_t(b)] += share;
        }
    for (int b = 0; b < K; ++b)
        if (lin[size_t(b)] > 0) out[b] = float(peak + kDbPerOctave * fast::log2_positive(lin[size_t(b)]));
}

/// The base grid's image sets the scale of what is worth refining (none when nothing is refined).
/// `rows_kept`: the image was set from these beams before some of them were emptied (groups sent to a
/// denser grid); only the emptied beams' rows change (each row depends on its own beam only).
void set_base_image(Sampler& sp, const Beams& beams, bool rows_kept = false) {
    const SceneDesc& s = sp.s;
    const int N = s.sonar.beams, K = s.sonar.range_bins;
    auto& base_db = sp.criteria.base_db;
    if (sp.elevation_levels == 0 && sp.azimuth_levels == 0) return base_db.clear();
    constexpr float none = -std::numeric_limits<float>::infinity();
    if (rows_kept && base_db.size() == size_t(N) * size_t(K)) {
        for (int i = 0; i < N; ++i)
            if (beams[size_t(i)].empty())
                std::fill_n(base_db.begin() + std::ptrdiff_t(size_t(i) * size_t(K)), K, none);
    } else {
        base_db.assign(size_t(N) * size_t(K), none);
        tbb::parallel_for(0, N, [&](int i) {
            base_echo(s, *sp.frame.grid, beams[size_t(i)], base_db.data() + size_t(i) * size_t(K));
        });
    }
    double peak = -std::numeric_limits<double>::infinity(), cells = 0;
    for (float v : base_db) peak = std::max(peak, double(v));
    for (const auto& b : beams)
        for (const auto& c : b) cells += double(c.nodes.size());
    sp.criteria.cell_share_db = -std::numeric_limits<double>::infinity();
    if (!std::isfinite(peak) || cells == 0) return;
    double sum = 0;
    for (float v : base_db) // bins without echo add nothing
        if (v > -std::numeric_limits<float>::infinity())
            sum += fast::exp2_nonpositive(kLog2_10Over10 * (double(v) - peak));
    sp.criteria.cell_share_db =
        peak + 10 * std::log10(kCellShare * s.sampling.tolerance_rel_l1 * sum / cells);
}

} // namespace

/// Whether fast's bump decision at base grid M0 may count the triples refinement will split at
/// kRefinableShare (past the first base grid; strict counts them in full).
static bool counts_refinable(const Sampler& sp, int M0) {
    return !sp.strict && M0 > sp.s.sampling.elevation_rays;
}

/// The base grid's images of each group's sample beam for its own error (sample_errors, estimated as the
/// refined image's is: against its sibling triples merged): the error that refinement, which works only at
/// discontinuities, starts from. Sets the sampler's reference level from the fine image.
struct BaseImages {
    PolarImage fine, coarse, edges;
};

static BaseImages base_images(Sampler& sp, const Beams& beams, const BeamGroups& groups) {
    const int sampled = int(groups.size());
    TraceResult fine, coarse, coarse_edges;
    fine.beams = coarse.beams = coarse_edges.beams = sampled;
    fine.cells.resize(size_t(sampled)), coarse.cells.resize(size_t(sampled));
    coarse_edges.cells.resize(size_t(sampled));
    tbb::parallel_for(0, sampled, [&](int k) { // without multipath: no ghosts
        for (const auto& c : beams[size_t(groups[size_t(k)].front())])
            sp.cells_of(c, c.da, {&fine.cells[size_t(k)]}, {&coarse.cells[size_t(k)]},
                        {&coarse_edges.cells[size_t(k)]});
    });
    BaseImages out{shade_columns(fine, sp.s, sampled), shade_columns(coarse, sp.s, sampled),
                   shade_columns(coarse_edges, sp.s, sampled)};
    sp.set_ref_db(out.fine);
    return out;
}

/// The same sample beams with only the triples merged that are neither smooth nor split by refinement
/// (refinable_triple, against the base image, which must be set).
static PolarImage lasting_edges_image(const Sampler& sp, const Beams& beams, const BeamGroups& groups) {
    const int sampled = int(groups.size());
    TraceResult lasting;
    lasting.beams = sampled;
    lasting.cells.resize(size_t(sampled));
    tbb::parallel_for(0, sampled, [&](int k) {
        for (const auto& c : beams[size_t(groups[size_t(k)].front())])
            sp.cells_of(c, c.da, {}, {}, {&lasting.cells[size_t(k)]}, true);
    });
    return shade_columns(lasting, sp.s, sampled);
}

/// Whether the azimuth probe looks at column c of a sample beam: it is still at the beam's base width
/// `base_da` (not split in azimuth; a split's triple holds the difference).
bool probed(const Column& c, double base_da) {
    return !c.sibling && c.da > 0.999 * base_da;
}

/// The base width of the columns of a sample beam's `cols`.
double probe_base_da(const Sampler& sp, const std::vector<Column>& cols) {
    const int beam = cols.empty() ? 0 : cols.front().beam;
    return sp.frame.grid->beam_width_rad(beam) / sp.columns(beam);
}

/// The rays the azimuth probe of a sample beam's columns asks for: two per probed cell.
std::uint64_t probe_rays_wanted(const Sampler& sp, const std::vector<Column>& cols) {
    const double base_da = probe_base_da(sp, cols);
    const auto every = size_t(sp.probe_every), first = every / 2;
    std::uint64_t n = 0;
    for (const Column& c : cols)
        if (probed(c, base_da) && c.nodes.size() > first)
            n += 2 * ((c.nodes.size() - first + every - 1) / every);
    return n;
}

/// The azimuth probe of a sample beam's columns `cols` (refined): on every probe_every-th cell of each
/// column still at the beam's base width (not split in azimuth), two more rays at a third of the width each
/// side, as long as `allowance` (its rays paid from the budget) lasts; those cells as one column (`one`)
/// and as three (`three`), appended, and with multipath their ghosts (`one_ghosts`, `three_ghosts`).
/// Returns the rays traced; `ghost_rays` gets the ghosts' rays.
std::uint64_t azimuth_probe(const Sampler& sp, const std::vector<Column>& cols, std::uint64_t allowance,
                            std::vector<Cell>& one, std::vector<Cell>& three,
                            std::vector<GhostCell>& one_ghosts, std::vector<GhostCell>& three_ghosts,
                            std::uint64_t& ghost_rays) {
    const double base_da = probe_base_da(sp, cols);
    std::uint64_t rays = 0;
    for (const Column& c : cols) {
        if (!probed(c, base_da)) continue;
        const double d3 = c.da / 3;
        const Angle a(c.a), a_lo(c.a - c.da / 2), a_hi(c.a + c.da / 2);
        const Angle m_lo(c.a - d3 / 2), m_hi(c.a + d3 / 2), p(c.a + d3), p_hi(c.a + c.da / 2), st(c.a - d3),
            st_lo(c.a - c.da / 2);
        for (size_t t = size_t(sp.probe_every / 2); t < c.nodes.size(); t += size_t(sp.probe_every)) {
            const Node& b = c.nodes[t];
            const Angle& e = b.angle;
            // Every probe cell spreads its echo with the trend the image's cell at this node has.
            const float slope = float(spread_slope(c.nodes, t, 1, sp.criteria.bin_m()));
            const auto add = [slope](std::vector<Cell>& to, Cell&& cell) {
                cell.spread_slope_per_m = slope;
                to.push_back(cell);
            };
            const Angle h(b.de / 2);
            const Angle lo(e.rad - h.rad, e, h, -1), hi(e.rad + h.rad, e, h, +1); // e -+ de/2
            if (rays + 2 > allowance) return rays; // the budget paid for no more
            rays += 2;
            if (b.hit) {
                add(one, detail::make_cell(sp.frame, *b.hit, a, e, a_lo, a_hi, lo, hi));
                add(three, detail::make_cell(sp.frame, *b.hit, a, e, m_lo, m_hi, lo, hi));
                if (sp.multipath) {
                    ghost_rays += sp.mp.ghosts(*b.hit, a, e, a_lo, a_hi, lo, hi, c.beam, one_ghosts, b.via);
                    ghost_rays += sp.mp.ghosts(*b.hit, a, e, m_lo, m_hi, lo, hi, c.beam, three_ghosts, b.via);
                }
            }
            const auto side = [&](const Angle& as, const Angle& as_lo, const Angle& as_hi) {
                const auto hit =
                    detail::first_hit(sp.g, sp.s, sp.frame.origin, sp.frame.dir(as, e), sp.frame.t_max);
                if (!hit) return;
                add(three, detail::make_cell(sp.frame, *hit, as, e, as_lo, as_hi, lo, hi));
                if (sp.multipath)
                    ghost_rays += sp.mp.ghosts(*hit, as, e, as_lo, as_hi, lo, hi, c.beam, three_ghosts);
            };
            side(p, m_hi, p_hi);
            side(st, st_lo, m_lo);
        }
    }
    return rays;
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
    bool base_image_set = false; // from every beam of this base grid
    if (bump && !sp.control.preview && !sp.multipath && M0 >= 9) {
        const BaseImages base = base_images(sp, beams, groups);
        EstimateImages images{&base.edges};
        out.bumped = (*bump)(sample_errors(base.coarse, base.fine, sp.ref_db, images));
        // Fewer groups go denser with the refinable triples counted at their share: worth deciding again
        // only where some went (the base image first: the triples' significance is judged against it).
        if (counts_refinable(sp, M0) &&
            std::find(out.bumped.begin(), out.bumped.end(), 1) != out.bumped.end()) {
            set_base_image(sp, beams);
            base_image_set = true;
            const PolarImage lasting = lasting_edges_image(sp, beams, groups);
            images.lasting_edges = &lasting;
            out.bumped = (*bump)(sample_errors(base.coarse, base.fine, sp.ref_db, images));
        }
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
        // Every group went denser: nothing is left here to refine, collect or estimate.
        if (std::find(out.bumped.begin(), out.bumped.end(), 0) == out.bumped.end()) return out;
    }
    set_base_image(sp, beams, base_image_set);
    // Ghosts far below the base image's direct echo are culled (multipath.hpp, kGhostCullShare).
    if (sp.multipath)
        sp.mp.set_cull_floor({&sp.criteria.base_db,
                              sp.criteria.tolerance_per_bin_db() + 10 * std::log10(detail::kGhostCullShare),
                              2, 1});
    std::vector<Column*> columns; // in beam order
    for (auto& cols : beams)
        for (auto& c : cols) columns.push_back(&c);
    sp.refine_columns(columns, M0, sp.ordered);
    sp.refine_azimuth(beams, M0, sp.ordered);
    if (sp.control.cancelled()) throw TraceCancelled();
    std::vector<int> samples(static_cast<size_t>(G), -1);
    for (int k = 0; k < G; ++k)
        if (!out.bumped[size_t(k)]) samples[size_t(k)] = groups[size_t(k)].front();
    // The azimuth probe, on every sample beam: neither the refinement's neighbour tests nor the coarse image
    // see how the scene varies across a column's width (column triples merge only while no split broke
    // them, and splits at edges break most). Strict acts on it, fast reports it.
    const bool probe = !sp.control.preview;
    std::uint64_t probe_rays = 0;
    if (probe) {
        out.az_one.beams = out.az_three.beams = G;
        out.az_one.cells.resize(size_t(G)), out.az_three.cells.resize(size_t(G));
        if (sp.multipath) out.az_one.ghosts.resize(size_t(G)), out.az_three.ghosts.resize(size_t(G));
        std::vector<std::uint64_t> r(static_cast<size_t>(G), 0), rg(static_cast<size_t>(G), 0);
        std::vector<std::uint64_t> allowance(static_cast<size_t>(G), 0); // paid in the groups' order
        for (int k = 0; k < G; ++k)
            if (samples[size_t(k)] >= 0)
                allowance[size_t(k)] =
                    sp.reserve_up_to(probe_rays_wanted(sp, beams[size_t(samples[size_t(k)])]));
        tbb::parallel_for(0, G, [&](int k) {
            const int i = samples[size_t(k)];
            if (i < 0) return;
            std::vector<GhostCell> one_ghosts, three_ghosts;
            r[size_t(k)] =
                azimuth_probe(sp, beams[size_t(i)], allowance[size_t(k)], out.az_one.cells[size_t(k)],
                              out.az_three.cells[size_t(k)], one_ghosts, three_ghosts, rg[size_t(k)]);
            if (!sp.multipath) return;
            // In the sample's slot whatever beam they arrive in: the probe sums |three - one|.
            for (auto* g : {&one_ghosts, &three_ghosts})
                for (auto& x : *g) x.beam = std::uint32_t(k);
            out.az_one.ghosts[size_t(k)] = std::move(one_ghosts);
            out.az_three.ghosts[size_t(k)] = std::move(three_ghosts);
        });
        for (auto x : r) probe_rays += x;
        for (auto x : rg) out.fine.multipath_rays += x;
    }
    collect_cells(sp, beams, samples, out.fine, out.coarse, out.coarse_edges); // adds the refined rays
    out.fine.rays_traced += probe_rays;
    out.fine.preview = sp.control.preview;
    return out;
}

} // namespace sonarsim::adaptive

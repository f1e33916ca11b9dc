#include "core/shading/estimate.hpp"

#include "core/base/units.hpp"
#include "core/grid/beam_tables.hpp"
#include "core/shading/accumulate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sonarsim {

namespace {

/// Footprint binning converges in second order of the cell on a smooth surface: the whole stratum's cells
/// change the image by three times the half strata's bias.
constexpr double kOrderShare = 3;

double quantile(std::vector<float>& v, double q) {
    if (v.empty()) return 0;
    const size_t k = std::min(v.size() - 1, size_t(q * double(v.size())));
    std::nth_element(v.begin(), v.begin() + long(k), v.end());
    return v[k];
}

/// The scene of n beams as an image of their own (the image channel needs no beam angles).
SceneDesc beams_scene(const SceneDesc& s, int n) {
    SceneDesc sub = s;
    sub.sonar.beams = n;
    sub.sonar.beam_table = kUniformBeams;
    return sub;
}

/// The sample beams' cells (and ghosts) as an image of their own, and their whole-stratum cells.
struct Samples {
    TraceResult cells;
    std::vector<std::vector<Cell>> coarse;
};

Samples samples_of(const TraceResult& hits) {
    Samples out;
    for (int i = 0; i < hits.beams; ++i) {
        if (hits.coarse_cells[size_t(i)].empty()) continue;
        out.cells.cells.push_back(hits.cells[size_t(i)]);
        out.coarse.push_back(hits.coarse_cells[size_t(i)]);
        if (hits.ghosts.empty()) continue;
        out.cells.ghosts.push_back(hits.ghosts[size_t(i)]);
        for (GhostCell& g : out.cells.ghosts.back()) g.beam = std::uint32_t(out.coarse.size() - 1);
    }
    out.cells.beams = int(out.coarse.size());
    return out;
}

} // namespace

BinErrors bin_errors(const TraceResult& cells, const std::vector<std::vector<Cell>>& coarse,
                     const SceneDesc& s, double ref_db) {
    const size_t n = size_t(cells.beams);
    TraceResult half[2], whole;
    for (TraceResult* t : {&half[0], &half[1], &whole}) {
        t->beams = int(n);
        t->cells.resize(n);
        if (!cells.ghosts.empty()) t->ghosts.resize(n);
    }
    for (size_t k = 0; k < n; ++k) {
        for (const Cell& c : cells.cells[k]) {
            Cell twice = c;
            twice.solid_angle_sr *= 2;
            half[c.half & 1].cells[k].push_back(twice);
        }
        whole.cells[k] = coarse[k];
        if (cells.ghosts.empty()) continue;
        for (const GhostCell& g : cells.ghosts[k]) { // a ghost keeps its cell in the whole-stratum image
            GhostCell twice = g;
            twice.cell.solid_angle_sr *= 2;
            half[g.cell.half & 1].ghosts[k].push_back(twice);
            whole.ghosts[k].push_back(g);
        }
    }
    const SceneDesc sub = beams_scene(s, int(n));
    const PolarImage a = shade(half[0], sub), b = shade(half[1], sub), w = shade(whole, sub);
    if (std::isnan(ref_db)) {
        double peak = -INFINITY;
        for (const PolarImage* img : {&a, &b})
            for (float v : img->level_db) peak = std::max(peak, double(v));
        ref_db = std::isfinite(peak) ? peak : 0;
    }
    auto linear = [&](float v) { return v > -INFINITY ? std::exp((double(v) - ref_db) * kLn10Over10) : 0.0; };
    BinErrors out;
    out.bins = a.bins, out.beams = int(n), out.ref_db = ref_db;
    const size_t m = a.level_db.size();
    out.level.resize(m), out.error.resize(m), out.variance.resize(m), out.footprint.resize(m);
    for (size_t c = 0; c < m; ++c) {
        const double ia = linear(a.level_db[c]), ib = linear(b.level_db[c]), iw = linear(w.level_db[c]);
        const double f = 0.5 * (ia + ib), v = 0.5 * std::abs(ia - ib), u = std::abs(iw - f) / kOrderShare;
        out.level[c] = f, out.variance[c] = v, out.footprint[c] = u, out.error[c] = std::hypot(v, u);
    }
    return out;
}

TraceResult::ErrorEstimate summarise(const std::vector<const BinErrors*>& errors) {
    TraceResult::ErrorEstimate est;
    double num = 0, den = 0, var = 0, bias = 0;
    std::vector<float> db;
    for (const BinErrors* e : errors)
        for (size_t c = 0; c < e->level.size(); ++c) {
            const double f = e->level[c];
            num += e->error[c], den += f, var += e->variance[c], bias += e->footprint[c];
            if (f > 0) db.push_back(float(10 * std::log10(1 + e->error[c] / f)));
        }
    if (!(den > 0)) return est;
    est.valid = true;
    est.rel_l1 = num / den;
    est.variance_rel_l1 = var / den, est.footprint_rel_l1 = bias / den;
    est.median_abs_db = quantile(db, 0.5);
    est.p95_abs_db = quantile(db, 0.95);
    return est;
}

TraceResult::ErrorEstimate estimate_error(const TraceResult& hits, const SceneDesc& s) {
    if (!hits.halves) return {};
    const Samples x = samples_of(hits);
    if (x.cells.beams == 0) return {};
    const BinErrors e = bin_errors(x.cells, x.coarse, s);
    TraceResult::ErrorEstimate est = summarise({&e});
    est.passes = hits.error_estimate.passes;
    est.budget_reached = hits.error_estimate.budget_reached;
    return est;
}

} // namespace sonarsim

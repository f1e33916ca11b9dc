#include "core/shading/estimate.hpp"

#include "core/base/units.hpp"
#include "core/shading/accumulate.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

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

} // namespace

TraceResult::ErrorEstimate estimate_error(const TraceResult& hits, const SceneDesc& s) {
    TraceResult::ErrorEstimate est;
    if (!hits.halves) return est;
    // Three images of the sample beams, as images of their own (a beam's image does not depend on the
    // others): each half alone at twice its weight, and every ray with its whole stratum as its cell.
    TraceResult half[2], whole;
    const bool ghosts = !hits.ghosts.empty();
    for (int i = 0; i < hits.beams; ++i) {
        if (hits.stratum_cells[size_t(i)].empty()) continue;
        for (TraceResult* t : {&half[0], &half[1], &whole}) {
            t->cells.emplace_back();
            if (ghosts) t->ghosts.emplace_back();
        }
        const auto k = std::uint32_t(whole.cells.size() - 1);
        for (const Cell& c : hits.cells[size_t(i)]) {
            half[c.half & 1].cells.back().push_back(c);
            half[c.half & 1].cells.back().back().solid_angle_sr *= 2;
        }
        whole.cells.back() = hits.stratum_cells[size_t(i)];
        if (!ghosts) continue;
        for (GhostCell g : hits.ghosts[size_t(i)]) { // a ghost keeps its cell in the whole-stratum image
            g.beam = k;
            whole.ghosts.back().push_back(g);
            g.cell.solid_angle_sr *= 2;
            half[g.cell.half & 1].ghosts.back().push_back(g);
        }
    }
    const int n = int(whole.cells.size());
    if (n == 0) return est;
    half[0].beams = half[1].beams = whole.beams = n;
    const PolarImage a = shade_columns(half[0], s, n), b = shade_columns(half[1], s, n),
                     w = shade_columns(whole, s, n);

    double peak = -INFINITY; // linear sums relative to the strongest level, far from double's limits
    for (const PolarImage* img : {&a, &b})
        for (float v : img->level_db) peak = std::max(peak, double(v));
    if (!std::isfinite(peak)) return est;
    auto linear = [&](float v) { return v > -INFINITY ? std::exp((double(v) - peak) * kLn10Over10) : 0.0; };
    double num = 0, den = 0, var = 0, bias = 0;
    std::vector<float> db;
    for (size_t c = 0; c < a.level_db.size(); ++c) {
        const double ia = linear(a.level_db[c]), ib = linear(b.level_db[c]), iw = linear(w.level_db[c]);
        const double f = 0.5 * (ia + ib), v = 0.5 * std::abs(ia - ib), u = std::abs(iw - f) / kOrderShare;
        const double e = std::hypot(v, u);
        num += e, den += f, var += v, bias += u;
        if (f > 0) db.push_back(float(10 * std::log10(1 + e / f)));
    }
    if (!(den > 0)) return est;
    est.valid = true;
    est.rel_l1 = num / den;
    est.variance_rel_l1 = var / den, est.footprint_rel_l1 = bias / den;
    est.median_abs_db = quantile(db, 0.5);
    est.p95_abs_db = quantile(db, 0.95);
    est.passes = 1;
    return est;
}

} // namespace sonarsim

#include "core/shading/estimate.hpp"

#include "core/grid/beam_tables.hpp"
#include "core/shading/accumulate.hpp"

#include <algorithm>
#include <cmath>

namespace sonarsim {

namespace {

constexpr double kLn10Over10 = 0.23025850929940458;
/// Footprint binning converges in second order of the cell on a smooth surface: merging pairs of strata
/// changes the image by three times the fine cells' bias.
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
    std::vector<int> sample;
    for (int i = 0; i < hits.beams; ++i)
        if (!hits.coarse_cells[size_t(i)].empty()) sample.push_back(i);
    const size_t n = sample.size();
    // Three images of the sample beams, as images of their own (a beam's image does not depend on the
    // others): each half alone (at twice its weight), and all cells with strata pairs merged.
    TraceResult half[2], coarse;
    for (TraceResult* t : {&half[0], &half[1], &coarse}) {
        t->beams = int(n);
        t->cells.resize(n);
        if (!hits.ghosts.empty()) t->ghosts.resize(n);
    }
    for (size_t k = 0; k < n; ++k) {
        const size_t i = size_t(sample[k]);
        for (const Cell& c : hits.cells[i]) {
            Cell twice = c;
            twice.solid_angle_sr *= 2;
            half[c.half & 1].cells[k].push_back(twice);
        }
        coarse.cells[k] = hits.coarse_cells[i];
        if (hits.ghosts.empty()) continue;
        for (const GhostCell& g : hits.ghosts[i]) { // ghosts keep their cells in both images
            GhostCell twice = g, same = g;
            twice.cell.solid_angle_sr *= 2, twice.beam = same.beam = std::uint32_t(k);
            half[g.cell.half & 1].ghosts[k].push_back(twice);
            coarse.ghosts[k].push_back(same);
        }
    }
    SceneDesc sub = s;
    sub.sonar.beams = int(n);
    sub.sonar.beam_table = kUniformBeams; // the image channel needs no beam angles
    const PolarImage a = shade(half[0], sub), b = shade(half[1], sub), w = shade(coarse, sub);
    double peak = -INFINITY;
    for (float v : a.level_db) peak = std::max(peak, double(v));
    for (float v : b.level_db) peak = std::max(peak, double(v));
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

// Adaptive sampling: a pass's refined columns as cells, fine and, on the sample beams, one level coarser
// (sibling triples merged: all of them, or only those that are not smooth), for the image and its error
// estimate.
#include "core/sampling/adaptive_sampler.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace sonarsim::adaptive {
namespace {

/// ln of a node's echo per metre of range; NaN: none. Its per_metre_db is that in dB where its footprint
/// spans a bin (set_width), else the echo per bin width.
double log_per_metre(const Node& n, double bin_m) {
    if (!n.hit || !(n.footprint_m > 0)) return std::numeric_limits<double>::quiet_NaN();
    const double db = n.footprint_m >= bin_m
                          ? n.per_metre_db
                          : n.per_metre_db + kDbPerOctave * fast::log2_positive(bin_m / n.footprint_m);
    return kLn10Over10 * db;
}

/// Whether nodes x and y, `reach` cells apart in a column, lie on one surface: one material, their ranges no
/// further apart than their footprints (times the reach) allow.
bool adjacent_on_one_surface(const Node& x, const Node& y, size_t reach, double bin_m) {
    return x.hit && y.hit && x.hit->material == y.hit->material &&
           std::abs(x.hit->t - y.hit->t) <=
               0.75 * double(reach) * (x.footprint_m + y.footprint_m) + 0.5 * bin_m;
}

/// The cells of one beam's columns (`fine`) and one level coarser: sibling column triples -> the middle
/// column, 3 da, and within each column every sibling elevation triple -> the middle cell (`all`); the same
/// with only the triples that are not smooth merged, columns and cells (`edges`). Each cell is made once
/// for the outputs that share it. Returns the ghosts' rays.
std::uint64_t coarse_cells_of(const Sampler& sp, const std::vector<Column>& cols, CellsOut fine, CellsOut all,
                              CellsOut edges) {
    std::uint64_t rays = 0;
    for (size_t k = 0; k < cols.size();) {
        if (k + 2 < cols.size() && cols[k].group == cols[k + 1].group && cols[k].group == cols[k + 2].group) {
            const bool smooth = sp.smooth_column_triple(cols, k);
            for (size_t t = k; t < k + 3; ++t)
                rays += sp.cells_of(cols[t], cols[t].da, fine, {}, smooth ? edges : CellsOut{});
            rays += sp.cells_of(cols[k + 1], 3 * cols[k + 1].da, {}, all, smooth ? CellsOut{} : edges);
            k += 3;
        } else {
            rays += sp.cells_of(cols[k], cols[k].da, fine, all, edges);
            ++k;
        }
    }
    return rays;
}

} // namespace

double spread_slope(const std::vector<Node>& nodes, size_t k, size_t reach, double bin_m,
                    const double* log_pm) {
    if (k < reach || k + reach >= nodes.size()) return 0;
    const Node &x = nodes[k - reach], &m = nodes[k], &y = nodes[k + reach];
    if (!adjacent_on_one_surface(x, m, reach, bin_m) || !adjacent_on_one_surface(m, y, reach, bin_m))
        return 0;
    auto log_of = [&](size_t i) { return log_pm ? log_pm[i] : log_per_metre(nodes[i], bin_m); };
    const double lm = log_of(k), d_x = log_of(k - reach) - lm, d_y = log_of(k + reach) - lm;
    const double step = kLn10Over10 * kTrendStepDb; // larger steps are a kink or an edge, not a trend
    if (!(std::abs(d_x) <= step && std::abs(d_y) <= step)) return 0;
    auto per_metre = [&](const Node& o, double d) {
        const double dr = o.hit->t - m.hit->t;
        return std::abs(dr) > 1e-9 ? d / dr : 0.0;
    };
    const double a = per_metre(x, d_x), b = per_metre(y, d_y);
    if (!(a * b > 0)) return 0;
    return std::abs(a) < std::abs(b) ? a : b;
}

void collect_cells(const Sampler& sp, Beams& beams, const std::vector<int>& samples, TraceResult& fine,
                   TraceResult& coarse, TraceResult& coarse_edges) {
    const SceneDesc& s = sp.s;
    const int N = s.sonar.beams, sampled = int(samples.size());
    std::vector<int> slot(static_cast<size_t>(N), -1); // beam -> its slot
    for (int k = 0; k < sampled; ++k)
        if (samples[size_t(k)] >= 0) slot[size_t(samples[size_t(k)])] = k;
    fine.beams = N, coarse.beams = coarse_edges.beams = sampled;
    coarse.cells.resize(size_t(sampled)), coarse_edges.cells.resize(size_t(sampled));
    fine.cells.resize(size_t(N));
    // Ghosts by the beam whose rays found them (the coarse ones on sample beams only), split as they are
    // made: those arriving wholly in that beam, and the others (`_away`), as gather_ghosts takes them.
    const size_t mp_beams = sp.multipath ? size_t(N) : 0;
    std::vector<std::vector<GhostCell>> fine_ghosts(static_cast<size_t>(N)), coarse_ghosts(mp_beams),
        edge_ghosts(mp_beams), fine_away(mp_beams), coarse_away(mp_beams), edge_away(mp_beams);
    auto out_of = [&](std::vector<Cell>& cells, std::vector<std::vector<GhostCell>>& ghosts,
                      std::vector<std::vector<GhostCell>>& away, int i) {
        if (!sp.multipath) return CellsOut{&cells};
        return CellsOut{&cells, &ghosts[size_t(i)], &away[size_t(i)]};
    };
    std::vector<std::uint64_t> ghost_rays(static_cast<size_t>(N), 0);
    tbb::parallel_for(0, N, [&](int i) {
        const auto& cols = beams[size_t(i)];
        size_t nodes = 0;
        for (auto& c : cols) nodes += c.nodes.size();
        fine.cells[size_t(i)].reserve(nodes);
        if (sp.multipath) { // bounces 1: at most three per cell, one of them from the scatterer's direction
            fine_ghosts[size_t(i)].reserve(2 * nodes);
            fine_away[size_t(i)].reserve(nodes);
        }
        const CellsOut out = out_of(fine.cells[size_t(i)], fine_ghosts, fine_away, i);
        if (sp.control.preview || slot[size_t(i)] < 0) {
            for (auto& c : cols) ghost_rays[size_t(i)] += sp.cells_of(c, c.da, out);
            return;
        }
        const size_t k = size_t(slot[size_t(i)]);
        if (sp.multipath) coarse_ghosts[size_t(i)].reserve(2 * nodes), coarse_away[size_t(i)].reserve(nodes);
        ghost_rays[size_t(i)] +=
            coarse_cells_of(sp, cols, out, out_of(coarse.cells[k], coarse_ghosts, coarse_away, i),
                            out_of(coarse_edges.cells[k], edge_ghosts, edge_away, i));
    });
    if (sp.multipath) {
        fine.ghosts = detail::gather_ghosts(fine_ghosts, fine_away, s);
        // The coarser images' ghosts: those arriving in each sample beam, in its slot.
        auto by_slot = [&](std::vector<std::vector<GhostCell>>& by_source,
                           std::vector<std::vector<GhostCell>>& away, TraceResult& r) {
            auto arriving = detail::gather_ghosts(by_source, away, s);
            r.ghosts.assign(size_t(sampled), {});
            for (int k = 0; k < sampled; ++k)
                if (samples[size_t(k)] >= 0)
                    r.ghosts[size_t(k)] = std::move(arriving[size_t(samples[size_t(k)])]);
        };
        by_slot(coarse_ghosts, coarse_away, coarse);
        by_slot(edge_ghosts, edge_away, coarse_edges);
        for (auto r : ghost_rays) fine.multipath_rays += r;
    }
    for (auto& b : beams)
        for (auto& c : b) fine.rays_traced += c.rays;
    beams.clear(); // the nodes are no longer needed: free them before shading
    beams.shrink_to_fit();
}

std::uint64_t Sampler::cells_of(const Column& c, double da, CellsOut fine, CellsOut all, CellsOut edges,
                                bool lasting_edges_only) const {
    std::uint64_t rays = 0;
    const Angle a(c.a), a_lo(c.a - da / 2), a_hi(c.a + da / 2);
    thread_local std::vector<GhostCell> made; // one cell's ghosts, before they go to each output
    thread_local std::vector<char> stays;     // per ghost in made: detail::stays_in_source
    const double bin_m = criteria.bin_m();
    const bool trend = !control.preview;     // a preview is the plain base grid
    thread_local std::vector<double> log_pm; // ln(echo per metre) of each node of c, for the trends
    if (trend) {
        log_pm.resize(c.nodes.size());
        for (size_t k = 0; k < c.nodes.size(); ++k) log_pm[k] = log_per_metre(c.nodes[k], bin_m);
    }
    auto slope = [&](size_t k, size_t reach) {
        return trend ? spread_slope(c.nodes, k, reach, bin_m, log_pm.data()) : 0.0;
    };
    auto emit = [&](const Node& n, double de, double trend_per_m, std::initializer_list<const CellsOut*> to) {
        if (!n.hit) return;
        const Angle& h = detail::half_angle(de); // widths come in a few sizes: kept per thread
        const Angle& e = n.angle;
        const Angle lo(e.rad - h.rad, e, h, -1), hi(e.rad + h.rad, e, h, +1); // e -+ de/2 (angle sums)
        Cell cell = detail::make_cell(frame, *n.hit, a, e, a_lo, a_hi, lo, hi);
        cell.spread_slope_per_m = float(trend_per_m);
        made.clear();
        if (multipath) {
            rays += mp.ghosts(*n.hit, a, e, a_lo, a_hi, lo, hi, c.beam, made, n.via);
            stays.resize(made.size());
            for (size_t k = 0; k < made.size(); ++k)
                stays[k] = detail::stays_in_source(made[k], size_t(c.beam), *frame.grid);
        }
        for (const CellsOut* o : to) {
            if (!o->cells) continue;
            o->cells->push_back(cell);
            if (!o->ghosts) continue;
            for (size_t k = 0; k < made.size(); ++k)
                (o->away && !stays[k] ? o->away : o->ghosts)->push_back(made[k]);
        }
    };
    const CellsOut none{};
    for (size_t n = 0; n < c.nodes.size();) {
        const bool triple = n + 2 < c.nodes.size() && c.nodes[n].group == c.nodes[n + 1].group &&
                            c.nodes[n].group == c.nodes[n + 2].group;
        if (!triple || (!all.cells && !edges.cells)) {
            emit(c.nodes[n], c.nodes[n].de, slope(n, 1), {&fine, &all, &edges});
            ++n;
            continue;
        }
        const bool smooth =
            edges.cells && (smooth_triple(c, n) || (lasting_edges_only && refinable_triple(c, n)));
        const CellsOut& fine_edges = smooth ? edges : none;
        if (fine.cells || smooth)
            for (size_t t = n; t < n + 3; ++t)
                emit(c.nodes[t], c.nodes[t].de, slope(t, 1), {&fine, &fine_edges});
        // The merged cell's trend from its neighbours at its level: the next triples' middles.
        if (all.cells || !smooth)
            emit(c.nodes[n + 1], 3 * c.nodes[n + 1].de, slope(n + 1, 3), {&all, smooth ? &none : &edges});
        n += 3;
    }
    return rays;
}

bool Sampler::smooth_triple(const Column& c, size_t n) const {
    const Node *x = &c.nodes[n], *m = &c.nodes[n + 1], *y = &c.nodes[n + 2];
    if (!x->hit || !m->hit || !y->hit) return false;
    const Angle a(c.a);
    const EdgeRay upper{a, x->angle.rad - x->de / 2, nullptr, &x->angle, x->de};
    const EdgeRay lower{a, m->angle.rad - m->de / 2, nullptr, &m->angle, m->de};
    if (criteria.edge_between(*x, *m, upper) || criteria.edge_between(*m, *y, lower)) return false;
    Node merged = *m; // the triple as one cell
    merged.de = 3 * m->de, merged.footprint_m = 3 * m->footprint_m;
    return !criteria.needs_split_alone(merged, a);
}

bool Sampler::refinable_triple(const Column& c, size_t n) const {
    const Angle a(c.a);
    for (size_t t = n; t < n + 2; ++t)
        if (criteria.splits_pair(c.nodes[t], c.nodes[t + 1], c, a)) return true;
    for (size_t t = n; t < n + 3; ++t)
        if (criteria.needs_split_alone(c.nodes[t], a)) return true;
    return false;
}

bool Sampler::smooth_column_triple(const std::vector<Column>& cols, size_t k) const {
    const Column &l = cols[k], &m = cols[k + 1], &r = cols[k + 2];
    if (l.base.empty() || m.base.empty() || r.base.empty()) return false;
    const int j0 = std::max({l.j0, m.j0, r.j0}), j1 = std::min({l.j1, m.j1, r.j1});
    if (j0 != m.j0 || j1 != m.j1) return false;
    const Angle port(0.5 * (l.a + m.a)), starboard(0.5 * (m.a + r.a));
    const double a_lo = std::min(l.a, r.a) - m.da / 2, a_hi = std::max(l.a, r.a) + m.da / 2;
    for (int j = j0; j < j1; ++j) {
        const Node &x = l.base[size_t(j - l.j0)], &y = m.base[size_t(j - m.j0)],
                   &z = r.base[size_t(j - r.j0)];
        if (!x.hit || !y.hit || !z.hit) return false;
        if (criteria.edge_between(x, y, EdgeRay{port, 0, &x.angle}) ||
            criteria.edge_between(y, z, EdgeRay{starboard, 0, &y.angle}))
            return false;
        if (criteria.specular_in_azimuth(y, a_lo, a_hi, 3 * m.da)) return false;
    }
    return true;
}

} // namespace sonarsim::adaptive

// Adaptive sampling: columns split in azimuth, only over the base cells where they disagree with their
// neighbours (or hold a specular lobe or an absorption step narrower than themselves).
#include "core/sampling/adaptive_sampler.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <iterator>
#include <utility>

namespace sonarsim::adaptive {
namespace {

/// One flag per base cell of each column of each beam.
using Marks = std::vector<std::vector<std::vector<char>>>;

/// Marks the base cells where neighbouring columns x and y (x to port) see different surfaces; mx and my
/// hold one flag per base cell of each.
void mark_disagreement(const Sampler& sp, const Column& x, const Column& y, std::vector<char>& mx,
                       std::vector<char>& my) {
    const Angle a_edge(0.5 * (x.a + y.a)); // the columns' shared azimuth edge
    for (int j = std::max(x.j0, y.j0); j < std::min(x.j1, y.j1); ++j) {
        const Node &nx = x.base[size_t(j - x.j0)], &ny = y.base[size_t(j - y.j0)];
        if (sp.criteria.discontinuous(nx, x, ny, y, EdgeRay{a_edge, 0, &nx.angle}))
            mx[size_t(j - x.j0)] = my[size_t(j - y.j0)] = 1;
    }
}

/// Level lv's neighbour comparisons in beam i: within the beam (after the first level only between the
/// siblings of a split) and, at the first level, across the beam's edges (each beam marks only its own
/// columns).
void mark_neighbours(const Sampler& sp, const Beams& beams, int i, int lv, int M0,
                     std::vector<std::vector<char>>& m) {
    const auto& cols = beams[size_t(i)];
    const int N = int(beams.size());
    if (cols.empty()) return; // a beam not traced (TraceControl::beams)
    for (size_t k = 0; k + 1 < cols.size(); ++k)
        if (lv == 0 || (cols[k].sibling && cols[k + 1].sibling && cols[k].group == cols[k + 1].group))
            mark_disagreement(sp, cols[k], cols[k + 1], m[k], m[k + 1]);
    if (lv != 0) return;
    std::vector<char> other(static_cast<size_t>(M0));
    // Across the beam's edges, with the nearest beam the image traces on each side: the next one, unless
    // the image traces only some beams (each ping's of a moving sonar, TraceControl::beams). Without a
    // neighbour a beam would never split in azimuth, an error the estimate does not see.
    int port = i - 1, starboard = i + 1;
    while (port >= 0 && !sp.control.traces(port)) --port;
    while (starboard < N && !sp.control.traces(starboard)) ++starboard;
    if (port >= 0 && !beams[size_t(port)].empty())
        mark_disagreement(sp, beams[size_t(port)].back(), cols.front(), other, m.front());
    if (starboard < N && !beams[size_t(starboard)].empty())
        mark_disagreement(sp, cols.back(), beams[size_t(starboard)].front(), m.back(), other);
}

/// Cells that need a narrower column on their own: a specular lobe or an absorption step across it.
/// Columns already at the finest width are left unmarked, and with `new_only` (after the first level) those
/// the last split did not make. Returns whether any cell is marked.
bool mark_alone(const Sampler& sp, const std::vector<Column>& cols, double min_da, bool new_only,
                std::vector<std::vector<char>>& m) {
    bool any = false;
    for (size_t k = 0; k < cols.size(); ++k) {
        const Column& c = cols[k];
        // At the finest width nothing splits; a column the last split left as it was was judged then.
        if (c.da <= min_da || (new_only && !c.sibling)) continue;
        const Angle a(c.a);
        for (auto& n : c.nodes)
            if (sp.criteria.specular_in_azimuth(n, c.a - c.da / 2, c.a + c.da / 2, c.da) ||
                sp.criteria.absorbed_across_azimuth(n, c, a))
                m[k][size_t(n.j - c.j0)] = 1;
        any = any || std::find(m[k].begin(), m[k].end(), 1) != m[k].end();
    }
    return any;
}

/// The runs [lo, hi) of base cells of column c to split: marked cells widened by kRunMargin each side.
std::vector<std::pair<int, int>> marked_runs(const Column& c, const std::vector<char>& marked) {
    const int n = c.j1 - c.j0;
    std::vector<std::pair<int, int>> runs;
    for (int j = 0; j < n; ++j) {
        bool m = false;
        for (int d = -kRunMargin; d <= kRunMargin && !m; ++d)
            m = j + d >= 0 && j + d < n && marked[size_t(j + d)];
        if (!m) continue;
        if (!runs.empty() && runs.back().second == c.j0 + j)
            ++runs.back().second;
        else
            runs.emplace_back(c.j0 + j, c.j0 + j + 1);
    }
    return runs;
}

/// Splits column c in three over each of `runs` (marked base cells widened by kRunMargin, paid for from the
/// budget): the middle takes c's rays there, two new columns are traced beside it over that run only and
/// refined at once (`ordered`: left `unrefined` for refine_columns). What c keeps outside the runs stays as
/// it is. Appends the results to `out`.
void split_column(const Sampler& sp, Column&& c, const std::vector<std::pair<int, int>>& runs, int M0,
                  bool ordered, int& next_group, std::vector<Column>& out) {
    std::vector<Column> triples;
    std::vector<char> moved(c.nodes.size(), 0);
    const double da = c.da / 3;
    for (auto [lo, hi] : runs) {
        Column mid;
        mid.a = c.a, mid.da = da, mid.beam = c.beam, mid.j0 = lo, mid.j1 = hi;
        // The nodes go down the column in elevation, so their base cells do not decrease: the run's nodes
        // are one range.
        const auto by_j = [](const Node& n, int j) { return n.j < j; };
        const auto first = std::lower_bound(c.nodes.begin(), c.nodes.end(), lo, by_j);
        const auto last = std::lower_bound(first, c.nodes.end(), hi, by_j);
        mid.nodes.assign(std::make_move_iterator(first), std::make_move_iterator(last));
        std::fill(moved.begin() + (first - c.nodes.begin()), moved.begin() + (last - c.nodes.begin()), 1);
        mid.base.assign(c.base.begin() + (lo - c.j0), c.base.begin() + (hi - c.j0));
        Column port = sp.trace_column(c.a + da, da, M0, c.beam, lo, hi); // port side first
        if (!ordered) sp.refine_column(port, M0);                        // while it is in the cache
        Column starboard = sp.trace_column(c.a - da, da, M0, c.beam, lo, hi);
        if (!ordered) sp.refine_column(starboard, M0);
        port.unrefined = starboard.unrefined = ordered;
        const int g = next_group++;
        for (Column* t : {&port, &mid, &starboard}) {
            t->group = g, t->sibling = true;
            triples.push_back(std::move(*t));
        }
    }
    // What stays of c: its cells outside the runs, never merged with others in the coarse image.
    Column rest = std::move(c);
    size_t kept = 0; // in place: the nodes not moved to a middle column, in order
    for (size_t k = 0; k < rest.nodes.size(); ++k)
        if (!moved[k]) {
            if (kept != k) rest.nodes[kept] = std::move(rest.nodes[k]);
            ++kept;
        }
    rest.nodes.erase(rest.nodes.begin() + long(kept), rest.nodes.end());
    rest.group = next_group++, rest.sibling = false;
    if (rest.nodes.empty() && !triples.empty())
        triples[1].rays += rest.rays; // the middle column of the first run took them all
    else
        out.push_back(std::move(rest));
    for (auto& t : triples) out.push_back(std::move(t));
}

/// Each column's runs to split, of one beam.
using Runs = std::vector<std::vector<std::pair<int, int>>>;

/// Replaces the columns of one beam by their splits over `runs`.
void split_marked_columns(const Sampler& sp, std::vector<Column>& cols, const Runs& runs, int M0,
                          bool ordered, int& next_group) {
    std::vector<Column> next;
    for (size_t k = 0; k < cols.size(); ++k) {
        if (runs[k].empty()) {
            cols[k].sibling = false;
            next.push_back(std::move(cols[k]));
        } else {
            split_column(sp, std::move(cols[k]), runs[k], M0, ordered, next_group, next);
        }
    }
    cols.swap(next);
}

} // namespace

void Sampler::refine_azimuth(Beams& beams, int M0, bool ordered) const {
    const int N = int(beams.size()), K0 = s.sampling.azimuth_rays;
    const double w = frame.grid->narrowest_beam_rad(); // columns split no finer than the narrowest beam's
    const double min_da = w / K0 / std::pow(3.0, kAzimuthLevels) * 1.0001;
    std::vector<int> next_group(static_cast<size_t>(N), 3 * K0 + 3); // above every base group id
    for (int lv = 0; lv < azimuth_levels; ++lv) {
        if (control.cancelled()) break;
        Marks mark(static_cast<size_t>(N));
        std::atomic<bool> any{false};
        tbb::parallel_for(0, N, [&](int i) {
            const auto& cols = beams[size_t(i)];
            auto& m = mark[size_t(i)];
            m.resize(cols.size());
            for (size_t k = 0; k < cols.size(); ++k) m[k].assign(size_t(cols[k].j1 - cols[k].j0), 0);
            if (lv < kEdgeAzimuthLevels) mark_neighbours(*this, beams, i, lv, M0, m);
            if (mark_alone(*this, cols, min_da, lv > 0, m)) any = true;
        });
        if (!any) break;
        // The runs to split, paid from the budget in the beams' and columns' order (a run refused stays as
        // it is), so that where the budget ends does not depend on the threads.
        std::vector<Runs> runs(static_cast<size_t>(N));
        for (int i = 0; i < N; ++i) {
            const auto& cols = beams[size_t(i)];
            runs[size_t(i)].resize(cols.size());
            for (size_t k = 0; k < cols.size(); ++k)
                for (auto run : marked_runs(cols[k], mark[size_t(i)][k]))
                    if (reserve(2 * std::uint64_t(run.second - run.first))) runs[size_t(i)][k].push_back(run);
        }
        tbb::parallel_for(0, N, [&](int i) {
            split_marked_columns(*this, beams[size_t(i)], runs[size_t(i)], M0, ordered,
                                 next_group[size_t(i)]);
        });
        std::vector<Column*> fresh; // the new columns beside each split, refined in elevation in order
        for (auto& cols : beams)
            for (auto& c : cols)
                if (c.unrefined) c.unrefined = false, fresh.push_back(&c);
        refine_columns(fresh, M0, ordered);
    }
}

} // namespace sonarsim::adaptive

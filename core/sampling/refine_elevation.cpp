// Adaptive sampling: tracing a column's cells and refining them in elevation.
#include "core/sampling/adaptive_sampler.hpp"

#include "core/shading/shade.hpp"

#include <algorithm>
#include <cmath>
#include <tbb/parallel_for.h>

namespace sonarsim::adaptive {

std::vector<double> pattern_grid(const ElevationWeight& w, double phi, int M) {
    std::vector<double> edges(size_t(M) + 1);
    if (w.flat()) {
        for (int j = 0; j <= M; ++j) edges[size_t(j)] = phi / 2 - j * (phi / M);
        return edges;
    }
    constexpr int kSteps = 4096;
    std::vector<double> F(kSteps + 1, 0.0); // the density's integral from the top, at e_k = phi/2 - k h
    const double h = phi / kSteps;
    auto rho = [&](int k) { return std::max(kTailDensity, std::pow(w(phi / 2 - k * h), kPatternExponent)); };
    double last = rho(0);
    for (int k = 0; k < kSteps; ++k) {
        const double next = rho(k + 1);
        F[size_t(k) + 1] = F[size_t(k)] + h * 0.5 * (last + next), last = next;
    }
    const int T = M / 3, R = M % 3; // whole triples, then R single cells
    const double units = T + R / 3.0, total = F.back();
    auto edge_at = [&](double mass) { // e where the integral from the top reaches mass
        const auto it = std::lower_bound(F.begin(), F.end(), mass);
        if (it == F.begin()) return phi / 2;
        if (it == F.end()) return -phi / 2;
        const size_t k = size_t(it - F.begin());
        const double f = (mass - F[k - 1]) / (F[k] - F[k - 1]);
        return phi / 2 - (double(k) - 1 + f) * h;
    };
    edges[0] = phi / 2, edges[size_t(M)] = -phi / 2;
    for (int t = 0; t < T; ++t) {
        const double top = edges[size_t(3 * t)];
        const double bottom = t + 1 == T && R == 0 ? -phi / 2 : edge_at(total * (t + 1) / units);
        for (int k = 1; k <= 3; ++k) edges[size_t(3 * t + k)] = top - k * (top - bottom) / 3;
    }
    for (int r = 1; r < R; ++r) edges[size_t(3 * T + r)] = edge_at(total * (T + r / 3.0) / units);
    return edges;
}

Sampler::Sampler(const SceneGeometry& geo, const SceneDesc& scene, const TraceControl& c)
    : g(geo), s(scene), control(c), frame(scene), multipath(detail::multipath_active(scene)),
      strict(scene.sampling.estimate == ErrorEstimate::Strict),
      probe_every(strict ? kProbeEvery : kFastProbeEvery), mp(geo, scene, frame),
      criteria(scene, frame, multipath), phi(frame.elevation_weight.traced_fov_rad()),
      elevation_levels(c.preview ? 0 : kElevationLevels), azimuth_levels(c.preview ? 0 : kAzimuthLevels) {
    for (int i = 0; i < scene.sonar.beams; ++i)
        if (c.traces(i)) traced.push_back(i);
    if (!frame.elevation_weight.flat()) // the flat pattern's even grid needs no edges (set_base_grid)
        first_edges = pattern_grid(frame.elevation_weight, phi, scene.sampling.elevation_rays);
}

void Sampler::set_base_grid(int M0) {
    for (auto& store : via_store) store.clear(); // the last pass's nodes are gone
    base_angles.resize(size_t(M0)), base_de.resize(size_t(M0)), base_de_min.resize(size_t(M0));
    const int M = s.sampling.elevation_rays;
    if (first_edges.empty()) { // even: as pattern_grid's, without rounding them through the edges
        const double de0 = phi / M0, de_min = phi / M / std::pow(3.0, kElevationLevels) * 1.0001;
        for (int j = 0; j < M0; ++j) base_angles[size_t(j)] = Angle(phi / 2 - (j + 0.5) * de0);
        std::fill(base_de.begin(), base_de.end(), de0);
        std::fill(base_de_min.begin(), base_de_min.end(), de_min);
        return;
    }
    // Each cell of the first grid split evenly into sub = M0 / elevation_rays cells (a power of 3), so that
    // a denser grid's cells are those a split of the coarser one's would make.
    const int sub = M0 / M;
    const double min_scale = 1.0001 / std::pow(3.0, kElevationLevels);
    for (int j0 = 0; j0 < M; ++j0) {
        const double top = first_edges[size_t(j0)], w = top - first_edges[size_t(j0) + 1], de = w / sub;
        for (int k = 0; k < sub; ++k) {
            const size_t j = size_t(j0 * sub + k);
            base_angles[j] = Angle(top - (k + 0.5) * de);
            base_de[j] = de, base_de_min[j] = w * min_scale;
        }
    }
}

bool Sampler::reserve(std::uint64_t n) const {
    if (rays.fetch_add(n, std::memory_order_relaxed) + n <= std::uint64_t(s.sampling.max_rays)) return true;
    rays.fetch_sub(n, std::memory_order_relaxed);
    budget_hit.store(true, std::memory_order_relaxed);
    return false;
}

std::uint64_t Sampler::reserve_up_to(std::uint64_t n) const {
    if (reserve(n)) return n;
    const std::uint64_t max = std::uint64_t(s.sampling.max_rays), used = rays.load(std::memory_order_relaxed);
    const std::uint64_t left = used < max ? (max - used) & ~std::uint64_t(1) : 0;
    if (left > 0) rays.fetch_add(left, std::memory_order_relaxed);
    return left;
}

Node Sampler::trace_node(const Angle& a, const Angle& e, double de, int group) const {
    Node n;
    n.de = de, n.group = group, n.angle = e;
    const glm::dvec3 d = frame.dir(a, n.angle);
    n.hit = detail::first_hit(g, s, frame.origin, d, frame.t_max);
    if (n.hit) {
        n.p_m = frame.origin + n.hit->t * d;
        n.density_db = cell_echo_db(criteria.constants(), material_of(s, n.hit->material), n.hit->t,
                                    std::abs(glm::dot(n.hit->normal, d)), frame.elevation_weight(e.rad));
        // On the face's plane (where the footprint lies, as in make_cell) r(e) = (n.(p - o)) / (n.d(e)), so
        // dr/de = -r (n.d_e) / (n.d).
        const glm::dvec3 d_e = frame.R * glm::dvec3(-n.angle.s * a.c, -n.angle.s * a.s, n.angle.c);
        const glm::dvec3& nf = n.hit->face_normal;
        n.dr_de = std::abs(n.hit->t * glm::dot(nf, d_e) / glm::dot(nf, d));
        set_width(n, de, criteria.bin_m());
        if (multipath) trace_continuation(n, a);
    }
    return n;
}

void Sampler::trace_continuation(Node& n, const Angle& a) const {
    auto& store = via_store.local();
    Via& via = store.emplace_back();
    n.via = &via;
    static_cast<detail::Multipath::Continuation&>(via) = mp.continuation(*n.hit, a, n.angle);
    if (!via.hit) return;
    const Hit& v = *via.hit;
    const double c = via.cos_at_hit;
    via.density_db = cell_echo_db(criteria.constants(), material_of(s, v.material), v.t, c,
                                  frame.elevation_weight(n.angle.rad));
    via.dr_de = v.t * std::min(1.0 / kLn10Over10, std::sqrt(std::max(0.0, 1 - c * c)) / std::max(c, 1e-9));
}

Column Sampler::trace_column(double a_rad, double da, int M0, int beam, int j0, int j1) const {
    Column col;
    col.a = a_rad, col.da = da, col.beam = beam, col.j0 = j0, col.j1 = j1;
    const Angle a(a_rad);
    col.nodes.reserve(size_t(j1 - j0));
    for (int j = j0; j < j1; ++j) {
        if (((j - j0) & 63) == 0 && control.cancelled()) return col;
        // Base triples share a group; the cells of an incomplete last triple get one each (never merged).
        const int group = j < M0 - M0 % 3 ? j / 3 : (M0 + 2) / 3 + j - (M0 - M0 % 3);
        col.nodes.push_back(trace_node(a, base_angles[size_t(j)], base_de[size_t(j)], group));
        col.nodes.back().j = j;
    }
    col.rays = std::uint64_t(j1 - j0);
    if (azimuth_levels > 0) col.base = col.nodes;
    return col;
}

void Sampler::densify_column(Column& col, int M0) const {
    const Angle a(col.a);
    for (auto& n : col.nodes) n.refine = true;
    int next_group = 0;
    split_marked(col, a, col.nodes.size(), next_group);
    // The new base cells, numbered and grouped as trace_column numbers them (M0 is a multiple of 3).
    for (size_t j = 0; j < col.nodes.size(); ++j) {
        Node& n = col.nodes[j];
        n.j = int(j), n.group = int(j) / 3, n.fresh = true, n.alone_checked = false;
    }
    col.j0 = 0, col.j1 = M0;
    if (azimuth_levels > 0) col.base = col.nodes;
}

size_t Sampler::mark_for_split(Column& col, const Angle& a) const {
    size_t marked = 0;
    auto mark = [&](Node& n) {
        if (n.de > base_de_min[size_t(n.j)] && !n.refine) n.refine = true, ++marked;
    };
    // Pairs of unchanged neighbours were compared before and found smooth: compare only fresh pairs.
    for (size_t n = 0; n + 1 < col.nodes.size(); ++n) {
        const Node &x = col.nodes[n], &y = col.nodes[n + 1];
        if ((x.fresh || y.fresh) && criteria.splits_pair(x, y, col, a))
            mark(col.nodes[n]), mark(col.nodes[n + 1]);
    }
    for (auto& n : col.nodes) n.fresh = false;
    for (auto& n : col.nodes)
        if (!n.refine && !n.alone_checked) {
            n.alone_checked = true;
            if (criteria.needs_split_alone(n, a)) mark(n);
        }
    return marked;
}

void Sampler::split_marked(Column& col, const Angle& a, size_t marked, int& next_group) const {
    // Into another vector, in column order: a marked node becomes three (the middle one is the node itself),
    // whose group numbers follow the column's order from the top. The vector is this thread's last
    // column's old one: nodes are large, and a column splits up to kElevationLevels times.
    thread_local std::vector<Node> out;
    out.clear();
    out.reserve(col.nodes.size() + 2 * marked);
    // Cells come in a few widths: keep sin and cos of the last third's.
    double h_de = 0;
    Angle h;
    for (Node& n : col.nodes) {
        if (!n.refine) {
            out.push_back(std::move(n));
            continue;
        }
        const double de = n.de / 3;
        const int grp = next_group++, j = n.j;
        if (de != h_de) h_de = de, h = Angle(de);
        const Angle up(n.angle.rad + de, n.angle, h, +1), down(n.angle.rad - de, n.angle, h, -1);
        out.push_back(trace_node(a, up, de, grp));
        out.back().j = j;
        Node& mid = out.emplace_back(std::move(n));
        mid.group = grp, mid.refine = false, mid.alone_checked = false;
        if (mid.hit)
            set_width(mid, de, criteria.bin_m());
        else
            mid.de = de, mid.fresh = true;
        out.push_back(trace_node(a, down, de, grp));
        out.back().j = j;
        col.rays += 2;
    }
    col.nodes.swap(out);
}

void Sampler::refine_column(Column& col, int M0) const {
    const Angle a(col.a);
    int next_group = M0 + 3; // above every base group id (j / 3, then one per cell of a partial triple)
    for (int level = 0; level < elevation_levels; ++level) {
        if (control.cancelled()) return;
        const size_t marked = mark_for_split(col, a);
        if (marked == 0 || !reserve(2 * marked)) break; // done, or the budget is spent
        split_marked(col, a, marked, next_group);
    }
}

void Sampler::refine_columns(const std::vector<Column*>& cols, int M0, bool ordered) const {
    // The finest cell has the same width in every pass (base_de_min): a denser base grid (a later pass)
    // refines fewer levels, so that its rays go to the cells the first pass left coarse, not deeper into
    // its edges.
    const size_t n = cols.size();
    if (!ordered) { // each column through all its levels at once, while its nodes are in the cache
        tbb::parallel_for(size_t(0), n, [&](size_t k) { refine_column(*cols[k], M0); });
        return;
    }
    // Level by level over all columns: each level's rays are taken from the budget in the columns' order,
    // then its splits and the next level's marks are made in parallel. A column refused stays at its level.
    std::vector<int> next_group(n, M0 + 3);
    std::vector<size_t> marked(n, 0);
    std::vector<char> active(n, 1);
    tbb::parallel_for(size_t(0), n,
                      [&](size_t k) { marked[k] = mark_for_split(*cols[k], Angle(cols[k]->a)); });
    for (int level = 0; level < elevation_levels; ++level) {
        if (control.cancelled()) return;
        bool any = false;
        for (size_t k = 0; k < n; ++k) {
            if (!active[k]) continue;
            if (marked[k] == 0 || !reserve(2 * marked[k])) active[k] = 0; // done, or the budget is spent
            any = any || active[k];
        }
        if (!any) return;
        const bool last = level + 1 == elevation_levels;
        tbb::parallel_for(size_t(0), n, [&](size_t k) { // this level's splits, then the next level's marks
            if (!active[k]) return;
            const Angle a(cols[k]->a);
            split_marked(*cols[k], a, marked[k], next_group[k]);
            marked[k] = last ? 0 : mark_for_split(*cols[k], a);
        });
    }
}

} // namespace sonarsim::adaptive

// Adaptive sampling: refine where the integrand of SONAR_MODEL.md is not smooth and the error that leaves
// in the image is significant against the tolerance; leave the rest coarse (see core/ARCHITECTURE.md).
#include "core/scene/params.hpp"
#include "core/shading/physics.hpp"
#include "core/analysis/reference.hpp"
#include "core/shading/accumulate.hpp"
#include "core/sampling/trace.hpp"
#include "core/sampling/multipath.hpp"
#include "core/sampling/trace_detail.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <tbb/parallel_for.h>

namespace sonarsim {

using detail::Angle;

namespace {

constexpr int kElevationLevels = 5; // ternary splits: cells down to 1/243 of the base width
constexpr int kAzimuthLevels = 3; // columns split in three locally: down to 1/27 of the base width (specular)
constexpr int kEdgeAzimuthLevels = 2; // ... and down to 1/9 where neighbouring columns see different surfaces
constexpr int kMaxPasses = 3;         // base refinements (x3) when the error estimate misses the tolerance
/// Cells whose errors may add up in one bin: a pair is worth refining when its possible error exceeds
/// 1 / kErrorsPerBin of what the tolerance allows the bin.
constexpr double kErrorsPerBin = 3;
/// The error estimate looks at every kEstimateStride-th beam of images with 8 x that many beams or more.
constexpr int kEstimateStride = 4;
/// An azimuth split covers the base cells where neighbouring columns disagree and this many on each side
/// (what differs between columns often moves in elevation from one to the next).
constexpr int kRunMargin = 1;

/// One elevation cell of a column.
struct Node {
    double e = 0, de = 0; ///< centre and width [rad]
    std::optional<Hit> hit;
    glm::dvec3 p{0};
    double density_db = 0;   ///< echo level per steradian (cell_echo_db with dOmega = B_v(e), the pattern)
    double dr_de = 0;        ///< |d range / d elevation| on the hit plane [m/rad]
    double footprint_m = 0;  ///< dr_de * de: the range the cell spans [m]
    double per_metre_db = 0; ///< echo per metre of range when the footprint spans bins (see set_width)
    bool fresh = true;       ///< created or resized since its neighbours were last compared
    int group = 0;           ///< siblings of one split (or base triples) share a group
    int j = 0;               ///< the base cell it lies in
    bool refine = false;
    bool alone_checked = false; ///< needs_split_alone() depends on the node only: evaluate it once
    Angle angle;                ///< e with its sine and cosine
    /// Multipath: what the specular continuation of a mirror hit meets, its echo per steradian as a double
    /// path (reflection losses aside) and |d range / d elevation| there.
    detail::Multipath::Continuation via;
    double via_density_db = 0, via_dr_de = 0;
};

struct Column {
    double a = 0, da = 0;
    int beam = 0;
    int j0 = 0, j1 = 0;      ///< the base cells [j0, j1) it covers (a split refines only where it is needed)
    bool sibling = false;    ///< made by the last azimuth split, beside its siblings (same group)
    int group = 0;           ///< sibling columns of one split (or base triples) share a group
    std::vector<Node> nodes; ///< ordered by decreasing elevation
    std::vector<Node> base;  ///< the base grid as first traced (for comparing neighbouring columns)
    std::uint64_t rays = 0;
};

struct Context {
    const SceneGeometry& g;
    const SceneDesc& s;
    const TraceControl& control;
    detail::RayFrame frame;
    bool multipath; ///< ghosts to find (sampling.bounces and a mirror)
    detail::Multipath mp;
    ShadeConstants k;
    double phi, jump_db, range_jump_db, bin_m, gap_m;
    double tol_rel_db; ///< 10 log10 of the relative error per bin that tolerance_db allows, 10^(tol/10) - 1
    int elevation_levels, azimuth_levels;
    mutable std::atomic<std::uint64_t> rays{0}; ///< rays traced or reserved in this image, all passes
    mutable std::atomic<bool> budget_hit{false};
    /// The base grid's image (L_EN per range bin and beam): the scale against which a neighbour pair's
    /// possible error is judged. Empty: every flagged pair counts.
    std::vector<float> base_db; ///< [beam * range_bins + bin]: echo [dB, as cell_echo_db] of the base grid
    Context(const SceneGeometry& geo, const SceneDesc& scene, const TraceControl& c)
        : g(geo), s(scene), control(c), frame(scene), multipath(detail::multipath_active(scene)),
          mp(geo, scene, frame), k(shade_constants(scene)), phi(frame.elevation_weight.traced_fov_rad()),
          jump_db(10 * scene.sampling.tolerance_db), range_jump_db(4 * scene.sampling.tolerance_db),
          bin_m((scene.sonar.range_max_m - scene.sonar.range_min_m) / scene.sonar.range_bins),
          gap_m(0.5 * bin_m),
          tol_rel_db(10 * std::log10((std::pow(10.0, scene.sampling.tolerance_db / 10) - 1) / kErrorsPerBin)),
          elevation_levels(c.preview ? 0 : kElevationLevels), azimuth_levels(c.preview ? 0 : kAzimuthLevels) {
    }

    /// Takes n rays from the image's budget (sampling.max_rays); false (and nothing taken) when it is spent.
    bool reserve(std::uint64_t n) const {
        if (rays.fetch_add(n, std::memory_order_relaxed) + n <= std::uint64_t(s.sampling.max_rays))
            return true;
        rays.fetch_sub(n, std::memory_order_relaxed);
        budget_hit.store(true, std::memory_order_relaxed);
        return false;
    }

    /// Sets the cell width and what follows from it for the neighbour comparisons.
    void set_width(Node& n, double de) const {
        n.de = de, n.fresh = true;
        n.footprint_m = n.dr_de * de;
        n.per_metre_db = n.density_db + 10 * std::log10(n.angle.c * de / std::max(n.footprint_m, bin_m));
    }

    Node trace_node(const Angle& a, const Angle& e, double de, int group) const {
        Node n;
        n.e = e.rad, n.de = de, n.group = group, n.angle = e;
        const glm::dvec3 d = frame.dir(a, n.angle);
        n.hit = detail::first_hit(g, s, frame.origin, d, frame.t_max);
        if (n.hit) {
            n.p = frame.origin + n.hit->t * d;
            n.density_db = cell_echo_db(k, material_of(s, n.hit->material), n.hit->t,
                                        std::abs(glm::dot(n.hit->normal, d)), frame.elevation_weight(e.rad));
            // On the hit plane r(e) = (n.(p - o)) / (n.d(e)), so dr/de = -r (n.d_e) / (n.d).
            const glm::dvec3 d_e = frame.R * glm::dvec3(-n.angle.s * a.c, -n.angle.s * a.s, n.angle.c);
            n.dr_de = std::abs(n.hit->t * glm::dot(n.hit->normal, d_e) / glm::dot(n.hit->normal, d));
            set_width(n, de);
            if (multipath) trace_continuation(n, a);
        }
        return n;
    }

    void trace_continuation(Node& n, const Angle& a) const {
        n.via = mp.continuation(*n.hit, a, n.angle);
        if (!n.via.hit) return;
        const Hit& v = *n.via.hit;
        const double c = n.via.cos_at_hit;
        n.via_density_db = cell_echo_db(k, material_of(s, v.material), v.t, c, frame.elevation_weight(n.e));
        n.via_dr_de =
            v.t * std::min(1.0 / kLn10Over10, std::sqrt(std::max(0.0, 1 - c * c)) / std::max(c, 1e-9));
    }

    /// Multipath: the continuations of neighbouring mirror cells x and y meet different surfaces, or one
    /// meets nothing, or their levels step, where that matters against the image (as for direct cells).
    bool via_discontinuous(const Node& x, const Column& cx, const Node& y, const Column& cy) const {
        if (!x.via.reflected && !y.via.reflected) return false;
        const bool hx = bool(x.via.hit), hy = bool(y.via.hit);
        if (hx != hy) return significant_via(hx ? x : y, hx ? cx : cy, 0.5);
        if (!hx) return false;
        const Hit &a = *x.via.hit, &b = *y.via.hit;
        const double reach = x.via_dr_de * x.de + y.via_dr_de * y.de + gap_m; // what a smooth surface spans
        const bool edge = a.material != b.material || (a.prim != b.prim && std::abs(a.t - b.t) > reach);
        if (edge) return significant_via(x, cx, 0.5) || significant_via(y, cy, 0.5);
        const double step_db = std::abs(x.via_density_db - y.via_density_db);
        if (step_db <= jump_db) return false;
        const double f = 0.5 * (1 - std::pow(10.0, -0.1 * step_db));
        return significant_via(x, cx, f) || significant_via(y, cy, f);
    }

    bool significant_via(const Node& n, const Column& c, double f) const {
        return n.via.hit && significant_at(n.via_density_db, n.via.hit->t, n.via_dr_de * n.de, n, c, f);
    }

    /// True when a surface edge lies between the hits of x and y: another material, or, on one object, hits
    /// on different triangles whose tangent planes disagree by more than half a range bin about where the
    /// ray `d_edge` along the cells' shared edge meets the surface (a silhouette, an occlusion, a crease
    /// that moves echo between bins). A finely tessellated smooth surface passes: its planes agree to second
    /// order in the spacing, so the number of rays does not grow with the number of triangles.
    template <class EdgeRay>
    bool surface_edge(const Hit& x, const glm::dvec3& px, const Hit& y, const glm::dvec3& py,
                      EdgeRay&& edge_ray) const {
        if (x.material != y.material) return true;
        if (x.material == kFloorMaterial || x.material == kSurfaceMaterial || x.prim == y.prim) return false;
        const glm::dvec3 d_edge = edge_ray();
        const double rx = detail::plane_range(frame.origin, px, x.normal, d_edge);
        const double ry = detail::plane_range(frame.origin, py, y.normal, d_edge);
        return rx < 0 || ry < 0 || std::abs(rx - ry) > gap_m;
    }

    /// Whether an error of a fraction `f` of the echo of node n's cell (in column c), spread over the
    /// cell's range footprint, exceeds the relative error per bin that the tolerance allows in the base
    /// image's bin of that range. Computed in dB, so that no level underflows.
    bool significant(const Node& n, const Column& c, double f) const {
        if (base_db.empty()) return true;
        return n.hit && significant_at(n.density_db, n.hit->t, n.footprint_m, n, c, f);
    }

    /// The same for an echo of `density_db` per steradian at range r spread over `footprint_m`.
    bool significant_at(double density_db, double r, double footprint_m, const Node& n, const Column& c,
                        double f) const {
        if (base_db.empty()) return true;
        if (!(f > 0)) return false;
        const double b = std::floor((r - s.sonar.range_min_m) / bin_m);
        if (!(b >= 0 && b < s.sonar.range_bins)) return false; // outside the window: no bin to spoil
        const double bin_db = base_db[size_t(c.beam) * size_t(s.sonar.range_bins) + size_t(b)]; // may be -inf
        const double error_db =
            density_db + 10 * std::log10(f * n.angle.c * n.de * c.da / std::max(1.0, footprint_m / bin_m));
        return error_db > tol_rel_db + bin_db;
    }

    /// A pair whose cells disagree (see discontinuous) is refined only where the error it can cause is
    /// significant against the image: half the echo of a cell at a surface edge, half the difference of the
    /// two levels on one surface. Pairs on rough surfaces whose cells are a small part of their bins' echo
    /// stay coarse; silhouettes, shadows and bright facets against their background do not.
    /// step_db: the difference of the two levels (a negative value: an edge).
    bool worth_refining(const Node& x, const Column& cx, const Node& y, const Column& cy,
                        double step_db) const {
        const double f = step_db < 0 ? 0.5 : 0.5 * (1 - std::pow(10.0, -0.1 * step_db));
        return significant(x, cx, f) || significant(y, cy, f);
    }

    /// Whether the cells of neighbours x (in column cx) and y (in cy) must be split: edge_ray() gives the
    /// ray along their shared edge (computed only when needed).
    template <class EdgeRay>
    bool discontinuous(const Node& x, const Column& cx, const Node& y, const Column& cy,
                       EdgeRay&& edge_ray) const {
        return discontinuous_direct(x, cx, y, cy, edge_ray) || (multipath && via_discontinuous(x, cx, y, cy));
    }

    template <class EdgeRay>
    bool discontinuous_direct(const Node& x, const Column& cx, const Node& y, const Column& cy,
                              EdgeRay&& edge_ray) const {
        if (bool(x.hit) != bool(y.hit)) return worth_refining(x, cx, y, cy, -1);
        if (!x.hit) return false;
        if (surface_edge(*x.hit, x.p, *y.hit, y.p, edge_ray)) return worth_refining(x, cx, y, cy, -1);
        const double density_step_db = std::abs(x.density_db - y.density_db);
        if (density_step_db > jump_db) return worth_refining(x, cx, y, cy, density_step_db);
        // Cells whose range footprint spans bins spread their echo evenly over it; where the echo per metre
        // of range changes between neighbours on one plane (grazing incidence: r(e) is far from linear over
        // the cell), that spreading needs finer cells. Between the facets of a smooth tessellated surface
        // the change is the facets' own (their normals step), and the density test above bounds it.
        if (x.hit->prim != y.hit->prim || !(std::max(x.footprint_m, y.footprint_m) > bin_m)) return false;
        const double per_metre_step_db = std::abs(x.per_metre_db - y.per_metre_db);
        return per_metre_step_db > range_jump_db && worth_refining(x, cx, y, cy, per_metre_step_db);
    }

    /// Direction of normal incidence on the node's plane, in the sonar frame.
    glm::dvec3 normal_direction_sonar(const Node& n) const {
        const glm::dvec3 v = glm::dot(n.hit->normal, n.p - frame.origin) > 0 ? n.hit->normal : -n.hit->normal;
        return glm::transpose(frame.R) * v;
    }

    /// A specular lobe narrower than the cell, centred inside it, or a plane horizon inside the cell.
    bool needs_split_alone(const Node& n, const Angle& a) const {
        if (!n.hit) return false;
        if (absorbed_across(n.footprint_m)) return true;
        const Material& m = material_of(s, n.hit->material);
        if (m.mu > 0 && n.de > deg2rad(m.h_deg) / 4) {
            const glm::dvec3 v = normal_direction_sonar(n);
            const double e_star = std::atan2(v.z, v.x * a.c + v.y * a.s);
            if (std::abs(e_star - n.e) < n.de / 2 + 2 * deg2rad(m.h_deg)) return true;
        }
        for (double edge : {n.e - n.de / 2, n.e + n.de / 2})
            if (detail::plane_range(frame.origin, n.p, n.hit->normal, frame.dir(a, Angle(edge))) < 0)
                return true;
        return false;
    }

    /// Absorption alone changes the echo by more than the range-spreading threshold across a cell's range
    /// footprint, which spreads its echo evenly (very high frequencies: at 10 MHz, 110 dB per metre of
    /// range; where a bin holds few cells, at the aperture's edges, the split of a cell's echo between bins
    /// must then follow the level within it).
    bool absorbed_across(double footprint_m) const {
        return 2 * k.alpha_db_per_m * footprint_m > range_jump_db;
    }

    /// The same across the column's azimuth width.
    bool absorbed_across_azimuth(const Node& n, const Column& c) const {
        if (!n.hit || !(k.alpha_db_per_m > 0)) return false;
        const Angle a(c.a);
        const glm::dvec3 d = frame.dir(a, n.angle);
        const glm::dvec3 d_a = frame.R * glm::dvec3(-n.angle.c * a.s, n.angle.c * a.c, 0);
        return absorbed_across(
            std::abs(n.hit->t * glm::dot(n.hit->normal, d_a) / glm::dot(n.hit->normal, d)) * c.da);
    }

    /// A specular lobe whose azimuth falls inside the beam [a_lo, a_hi] and is narrower than its columns.
    bool specular_in_azimuth(const Node& n, double a_lo, double a_hi, double da) const {
        if (!n.hit) return false;
        const Material& m = material_of(s, n.hit->material);
        if (!(m.mu > 0) || da <= deg2rad(m.h_deg) / 4) return false;
        const glm::dvec3 v = normal_direction_sonar(n);
        const double a_star = std::atan2(v.y, v.x), h = deg2rad(m.h_deg);
        return a_star > a_lo - 2 * h && a_star < a_hi + 2 * h;
    }

    /// The base grid's echo per bin of one beam, for significant(): each cell's echo spread evenly over its
    /// range footprint (a cheap stand-in for shading the base cells), summed relative to the beam's peak.
    void base_echo(const std::vector<Column>& cols, int beam) {
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
        float* out = base_db.data() + size_t(beam) * size_t(K);
        for (int b = 0; b < K; ++b)
            if (lin[size_t(b)] > 0) out[b] = float(peak + 10 * std::log10(lin[size_t(b)]));
    }

    /// The base grid of one column: base cells [j0, j1) of M0.
    Column trace_column(double a_rad, double da, int M0, int beam, int j0, int j1) const {
        Column col;
        col.a = a_rad, col.da = da, col.beam = beam, col.j0 = j0, col.j1 = j1;
        const Angle a(a_rad);
        const double de0 = phi / M0;
        col.nodes.reserve(size_t(j1 - j0));
        for (int j = j0; j < j1; ++j) {
            if (((j - j0) & 63) == 0 && control.cancelled()) return col;
            // Base triples share a group; the cells of an incomplete last triple get one each (never merged).
            const int group = j < M0 - M0 % 3 ? j / 3 : (M0 + 2) / 3 + j - (M0 - M0 % 3);
            col.nodes.push_back(trace_node(a, Angle(phi / 2 - (j + 0.5) * de0), de0, group));
            col.nodes.back().j = j;
        }
        col.rays = std::uint64_t(j1 - j0);
        if (azimuth_levels > 0) col.base = col.nodes;
        return col;
    }

    /// Ternary refinement of a column's cells down to kElevationLevels.
    void refine_column(Column& col, int M0) const {
        const Angle a(col.a);
        const double de0 = phi / M0, de_min = de0 / std::pow(3.0, kElevationLevels) * 1.0001;
        int next_group = M0 + 3; // above every base group id (j / 3, then one per cell of a partial triple)
        for (int level = 0; level < elevation_levels; ++level) {
            if (control.cancelled()) return;
            size_t marked = 0;
            auto mark = [&](Node& n) {
                if (n.de > de_min && !n.refine) n.refine = true, ++marked;
            };
            // Pairs of unchanged neighbours were compared before and found smooth: compare only fresh pairs.
            for (size_t n = 0; n + 1 < col.nodes.size(); ++n) {
                const Node &x = col.nodes[n], &y = col.nodes[n + 1];
                if ((x.fresh || y.fresh) &&
                    discontinuous(x, col, y, col, [&] { return frame.dir(a, Angle(x.e - x.de / 2)); }))
                    mark(col.nodes[n]), mark(col.nodes[n + 1]);
            }
            for (auto& n : col.nodes) n.fresh = false;
            for (auto& n : col.nodes)
                if (!n.refine && !n.alone_checked) {
                    n.alone_checked = true;
                    if (needs_split_alone(n, a)) mark(n);
                }
            if (marked == 0) break;
            if (!reserve(2 * marked)) break; // budget spent: this column stays at its current level
            std::vector<Node> next;
            next.reserve(col.nodes.size() + 2 * marked);
            for (auto& n : col.nodes) {
                if (!n.refine) {
                    next.push_back(n);
                    continue;
                }
                const double de = n.de / 3;
                const int grp = next_group++;
                const Angle h(de), up(n.e + de, n.angle, h, +1), down(n.e - de, n.angle, h, -1);
                next.push_back(trace_node(a, up, de, grp));
                next.back().j = n.j;
                Node mid = n;
                mid.group = grp, mid.refine = false, mid.alone_checked = false;
                if (mid.hit)
                    set_width(mid, de);
                else
                    mid.de = de, mid.fresh = true;
                next.push_back(mid);
                next.push_back(trace_node(a, down, de, grp));
                next.back().j = n.j;
                col.rays += 2;
            }
            col.nodes.swap(next);
        }
    }

    /// Cells of a column, and their multipath ghosts (with multipath); `coarse` merges every complete
    /// sibling triple into its middle cell (one level up). Returns the ghosts' rays.
    std::uint64_t cells_of(const Column& c, bool coarse, double da, std::vector<Cell>& out,
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
            if (multipath) rays += mp.ghosts(*n.hit, a, e, a_lo, a_hi, lo, hi, ghosts, &n.via);
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
};

/// Azimuth centre of column k of K in beam i (column 0 is the port-most).
double column_azimuth(const SceneDesc& s, int i, int k, int K) {
    const double theta = deg2rad(s.sonar.azimuth_fov_deg), w = theta / s.sonar.beams;
    return theta / 2 - i * w - (k + 0.5) * w / K;
}

/// Marks the base cells where neighbouring columns x and y (x to port) see different surfaces; mx and my
/// hold one flag per base cell of each.
void mark_disagreement(const Context& ctx, const Column& x, const Column& y, std::vector<char>& mx,
                       std::vector<char>& my) {
    const Angle a_edge(0.5 * (x.a + y.a)); // the columns' shared azimuth edge
    for (int j = std::max(x.j0, y.j0); j < std::min(x.j1, y.j1); ++j) {
        const Node &nx = x.base[size_t(j - x.j0)], &ny = y.base[size_t(j - y.j0)];
        if (ctx.discontinuous(nx, x, ny, y, [&] { return ctx.frame.dir(a_edge, nx.angle); }))
            mx[size_t(j - x.j0)] = my[size_t(j - y.j0)] = 1;
    }
}

/// Splits column c in three over each run of marked base cells (widened by one cell each side): the
/// middle takes c's rays there, two new columns are traced beside it over that run only. What c keeps
/// outside the runs stays as it is. Appends the results to `out`.
void split_column(const Context& ctx, Column&& c, const std::vector<char>& marked, int M0, int& next_group,
                  std::vector<Column>& out) {
    const int n = c.j1 - c.j0;
    std::vector<std::pair<int, int>> runs; // [lo, hi) in base cells
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
    std::vector<Column> triples;
    std::vector<char> moved(c.nodes.size(), 0);
    const double da = c.da / 3;
    for (auto [lo, hi] : runs) {
        if (!ctx.reserve(2 * std::uint64_t(hi - lo))) continue; // budget spent: this run stays as it is
        Column mid;
        mid.a = c.a, mid.da = da, mid.beam = c.beam, mid.j0 = lo, mid.j1 = hi;
        for (size_t k = 0; k < c.nodes.size(); ++k)
            if (c.nodes[k].j >= lo && c.nodes[k].j < hi) mid.nodes.push_back(c.nodes[k]), moved[k] = 1;
        mid.base.assign(c.base.begin() + (lo - c.j0), c.base.begin() + (hi - c.j0));
        Column port = ctx.trace_column(c.a + da, da, M0, c.beam, lo, hi); // port side first
        ctx.refine_column(port, M0);
        Column starboard = ctx.trace_column(c.a - da, da, M0, c.beam, lo, hi);
        ctx.refine_column(starboard, M0);
        const int g = next_group++;
        for (Column* t : {&port, &mid, &starboard}) {
            t->group = g, t->sibling = true;
            triples.push_back(std::move(*t));
        }
    }
    // What stays of c: its cells outside the runs, never merged with others in the coarse image.
    Column rest = std::move(c);
    std::vector<Node> kept;
    for (size_t k = 0; k < rest.nodes.size(); ++k)
        if (!moved[k]) kept.push_back(std::move(rest.nodes[k]));
    rest.nodes.swap(kept);
    rest.group = next_group++, rest.sibling = false;
    if (rest.nodes.empty() && !triples.empty())
        triples[1].rays += rest.rays; // the middle column of the first run took them all
    else
        out.push_back(std::move(rest));
    for (auto& t : triples) out.push_back(std::move(t));
}

TraceResult trace_pass(Context& ctx, int M0, TraceResult::ErrorEstimate& est) {
    const SceneDesc& s = ctx.s;
    const int N = s.sonar.beams, K0 = s.sampling.azimuth_rays;
    const double w = deg2rad(s.sonar.azimuth_fov_deg) / N;
    std::vector<std::vector<Column>> beams(static_cast<size_t>(N));
    ctx.rays.fetch_add(std::uint64_t(N) * K0 * M0); // the base grid is always traced
    tbb::parallel_for(0, N, [&](int i) {
        for (int k = 0; k < K0; ++k) {
            beams[size_t(i)].push_back(ctx.trace_column(column_azimuth(s, i, k, K0), w / K0, M0, i, 0, M0));
            beams[size_t(i)].back().group = k / 3 + (K0 % 3 && k >= K0 - K0 % 3 ? K0 + k : 0);
        }
    });
    // The base grid's echo per bin sets the scale of what is worth refining; then each column refines in
    // elevation.
    ctx.base_db.clear();
    if (ctx.elevation_levels > 0 || ctx.azimuth_levels > 0) {
        ctx.base_db.assign(size_t(N) * size_t(s.sonar.range_bins), -std::numeric_limits<float>::infinity());
        tbb::parallel_for(0, N, [&](int i) { ctx.base_echo(beams[size_t(i)], i); });
    }
    tbb::parallel_for(0, N, [&](int i) {
        for (auto& c : beams[size_t(i)]) ctx.refine_column(c, M0);
    });
    // Columns that see different surfaces than their neighbours (within the beam or across its edges), or
    // that hold a specular lobe narrower than themselves, split in three where they do (see split_column).
    // After the first level, only the siblings of a split are compared with each other.
    std::vector<int> next_group(static_cast<size_t>(N), 3 * K0 + 3); // above every base group id
    for (int lv = 0; lv < ctx.azimuth_levels; ++lv) {
        if (ctx.control.cancelled()) break;
        std::vector<std::vector<std::vector<char>>> mark(static_cast<size_t>(N));
        std::atomic<bool> any{false};
        tbb::parallel_for(0, N, [&](int i) {
            const auto& cols = beams[size_t(i)];
            auto& m = mark[size_t(i)];
            m.resize(cols.size());
            for (size_t k = 0; k < cols.size(); ++k) m[k].assign(size_t(cols[k].j1 - cols[k].j0), 0);
            const double min_da = w / K0 / std::pow(3.0, kAzimuthLevels) * 1.0001;
            if (lv < kEdgeAzimuthLevels) {
                for (size_t k = 0; k + 1 < cols.size(); ++k)
                    if (lv == 0 ||
                        (cols[k].sibling && cols[k + 1].sibling && cols[k].group == cols[k + 1].group))
                        mark_disagreement(ctx, cols[k], cols[k + 1], m[k], m[k + 1]);
                if (lv == 0) { // across the beam's edges: each beam marks only its own columns
                    std::vector<char> other(static_cast<size_t>(M0));
                    if (i > 0)
                        mark_disagreement(ctx, beams[size_t(i) - 1].back(), cols.front(), other, m.front());
                    if (i + 1 < N)
                        mark_disagreement(ctx, cols.back(), beams[size_t(i) + 1].front(), m.back(), other);
                }
            }
            for (size_t k = 0; k < cols.size(); ++k) {
                const Column& c = cols[k];
                for (auto& n : c.nodes)
                    if (ctx.specular_in_azimuth(n, c.a - c.da / 2, c.a + c.da / 2, c.da) ||
                        ctx.absorbed_across_azimuth(n, c))
                        m[k][size_t(n.j - c.j0)] = 1;
                if (c.da <= min_da) std::fill(m[k].begin(), m[k].end(), 0);
                for (char f : m[k])
                    if (f) {
                        any = true;
                        break;
                    }
            }
        });
        if (!any) break;
        tbb::parallel_for(0, N, [&](int i) {
            auto& cols = beams[size_t(i)];
            std::vector<Column> next;
            for (size_t k = 0; k < cols.size(); ++k) {
                const auto& mk = mark[size_t(i)][k];
                if (std::find(mk.begin(), mk.end(), 1) == mk.end()) {
                    cols[k].sibling = false;
                    next.push_back(std::move(cols[k]));
                } else {
                    split_column(ctx, std::move(cols[k]), mk, M0, next_group[size_t(i)], next);
                }
            }
            cols.swap(next);
        });
    }

    if (ctx.control.cancelled()) throw TraceCancelled();
    // The error estimate compares the image with the same cells one level coarser on every
    // kEstimateStride-th beam (all beams of narrow images): a sample of the image, at a quarter of the cost.
    // With multipath every beam: ghosts arrive in beams other than their rays'.
    const int stride = N >= 8 * kEstimateStride && !ctx.multipath ? kEstimateStride : 1,
              sampled = (N + stride - 1) / stride;
    TraceResult fine, coarse;
    fine.beams = N, coarse.beams = sampled;
    coarse.cells.resize(size_t(sampled)), fine.cells.resize(size_t(N));
    std::vector<std::vector<GhostCell>> fine_ghosts(static_cast<size_t>(N)),
        coarse_ghosts(static_cast<size_t>(sampled));
    std::vector<std::uint64_t> ghost_rays(static_cast<size_t>(N), 0);
    tbb::parallel_for(0, N, [&](int i) {
        const auto& cols = beams[size_t(i)];
        for (auto& c : cols)
            ghost_rays[size_t(i)] +=
                ctx.cells_of(c, false, c.da, fine.cells[size_t(i)], fine_ghosts[size_t(i)]);
        if (ctx.control.preview || i % stride) return;
        auto& coarse_cells = coarse.cells[size_t(i / stride)];
        auto& coarse_ghost = coarse_ghosts[size_t(i / stride)];
        // One level coarser everywhere: sibling column triples -> the middle column (3 da), and within each
        // column sibling elevation triples -> the middle cell.
        for (size_t k = 0; k < cols.size();) {
            if (k + 2 < cols.size() && cols[k].group == cols[k + 1].group &&
                cols[k].group == cols[k + 2].group) {
                ghost_rays[size_t(i)] +=
                    ctx.cells_of(cols[k + 1], true, 3 * cols[k + 1].da, coarse_cells, coarse_ghost);
                k += 3;
            } else {
                ghost_rays[size_t(i)] += ctx.cells_of(cols[k], true, cols[k].da, coarse_cells, coarse_ghost);
                ++k;
            }
        }
    });
    if (ctx.multipath) {
        fine.ghosts = detail::gather_ghosts(fine_ghosts, s);
        coarse.ghosts = detail::gather_ghosts(coarse_ghosts, s);
        for (auto r : ghost_rays) fine.multipath_rays += r;
    }
    for (auto& b : beams)
        for (auto& c : b) fine.rays_traced += c.rays;
    beams.clear(); // the nodes are no longer needed: free them before shading
    beams.shrink_to_fit();
    Channels channels = ctx.control.channels; // with the image: the estimate below needs it
    channels.image = true;
    auto shaded = std::make_shared<const Accumulation>(accumulate(fine, s, channels));
    const PolarImage& fine_image = *shaded->image;
    if (ctx.control.preview) {
        fine.shaded = std::move(shaded);
        fine.preview = true;
        return fine;
    }
    // The sampled beams as an image of their own (shade() sums beam by beam, so a beam's image does not
    // depend on the others).
    SceneDesc sampled_scene = s;
    sampled_scene.sonar.beams = sampled;
    PolarImage fine_sampled;
    fine_sampled.bins = fine_image.bins, fine_sampled.beams = sampled;
    fine_sampled.level_db.resize(size_t(fine_image.bins) * size_t(sampled));
    for (int b = 0; b < fine_image.bins; ++b)
        for (int i = 0; i < sampled; ++i)
            fine_sampled.level_db[size_t(b) * size_t(sampled) + size_t(i)] = fine_image.at(b, i * stride);
    const ImageError e = compare_images(shade(coarse, sampled_scene), fine_sampled);
    fine.shaded = std::move(shaded); // the caller need not shade these cells again
    // The coarse image's error is taken as three times the fine one's (first order at discontinuities, the
    // slowest case): fine error ~ |fine - coarse| / 2.
    est.valid = true;
    est.rel_l1 = e.rel_l1 / 2, est.median_abs_db = e.median_abs_db / 2, est.p95_abs_db = e.p95_abs_db / 2;
    return fine;
}

} // namespace

TraceResult trace_adaptive(const SceneGeometry& g, const SceneDesc& s, const TraceControl& control) {
    Context ctx(g, s, control);
    std::uint64_t rays = 0, multipath_rays = 0;
    int M0 = s.sampling.elevation_rays;
    TraceResult out;
    for (int pass = 1;; ++pass) {
        TraceResult::ErrorEstimate est;
        out = trace_pass(ctx, M0, est);
        rays += out.rays_traced;
        multipath_rays += out.multipath_rays;
        est.passes = pass;
        est.budget_reached = ctx.budget_hit.load();
        out.error_estimate = est;
        // A denser base grid must fit in what is left of the budget.
        const double next_base = double(M0) * 3 * s.sonar.beams * s.sampling.azimuth_rays;
        if (out.preview || est.median_abs_db <= s.sampling.tolerance_db || pass == kMaxPasses ||
            est.budget_reached || next_base > kMaxRaysPerImage / 9 ||
            double(ctx.rays.load()) + next_base > double(s.sampling.max_rays)) {
            if (!out.preview && est.median_abs_db > s.sampling.tolerance_db && !est.budget_reached &&
                pass<kMaxPasses&& double(ctx.rays.load()) + next_base> double(s.sampling.max_rays))
                out.error_estimate.budget_reached = true; // the next pass would not fit
            break;
        }
        M0 *= 3;
    }
    out.rays_traced = rays;
    out.multipath_rays = multipath_rays;
    return out;
}

} // namespace sonarsim

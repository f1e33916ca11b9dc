// Jittered placement, refined where its own estimate says. A beam's aperture is cut into strata (at first
// azimuth_rays x elevation_rays of its width and of the traced aperture); each holds two independent
// antithetic pairs of rays (a point drawn uniformly in the stratum by a seeded hash, and its mirror about
// the stratum's centre): the pairs are two independent estimates of the image (Cell::half), each second
// order on a smooth surface as the midpoint rule is. Each ray's cell is the half of its stratum (in
// elevation) it falls in; the pair's two rays fall in opposite halves.
// Passes: the image's error is estimated on sample beams (every stride-th) by range bands (estimate.hpp);
// while it misses sampling.tolerance_rel_l1 or tolerance_db, the bands with the largest shares have their
// groups' strata that reach them split in two, along the longer side of the stratum on the surface. A
// split keeps the stratum's four rays (each is uniform in the child it fell in) and traces the mirror of
// each inside its child: no ray is traced twice, and the same scene always traces the same rays.
#include "core/sampling/trace.hpp"

#include "core/sampling/multipath.hpp"
#include "core/sampling/trace_detail.hpp"
#include "core/shading/estimate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <tbb/parallel_for.h>

namespace sonarsim {

namespace {

using detail::Angle;

/// About this many beams of an image are the estimate's samples (every stride-th traced beam).
constexpr int kEstimateBeams = 32;
/// Range bands per sample beam: the regions the estimate ranks.
constexpr int kBands = 16;
constexpr int kMaxPasses = 10;
/// A region whose strata split is taken to keep this share of its error (second order: a quarter; at
/// edges, where the error is first order, a half).
constexpr double kRefinedShare = 0.4;
/// Regions are taken until what is left meets this fraction of each tolerance.
constexpr double kAim = 0.75;
/// Cosine of incidence below which a stratum's extent on the surface is taken as at this grazing angle.
constexpr double kMinCosIncidence = 0.05;

constexpr std::uint64_t mix(std::uint64_t x) { // splitmix64's finaliser
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

/// Two uniforms in [0, 1) for pair `pair` of the stratum with key `key`.
std::pair<double, double> jitter(std::uint64_t key, int pair) {
    const std::uint64_t a = mix(key ^ (std::uint64_t(pair) + 1) * 0xD1B54A32D192ED03ull), b = mix(a);
    return {double(a >> 11) * 0x1.0p-53, double(b >> 11) * 0x1.0p-53};
}

struct Ray {
    Angle a, e;
    bool traced = false, hit = false;
    Hit h;
};

/// [a_lo, a_hi] x [e_lo, e_hi] and its rays: ray[0] and ray[1] one antithetic pair (half 0), ray[2] and
/// ray[3] the other (half 1).
struct Stratum {
    Angle a_lo, a_hi, a_c, e_lo, e_hi, e_mid, e_top_c, e_bottom_c;
    std::uint64_t key = 0;
    std::uint32_t ray[4] = {0, 0, 0, 0};
    Stratum() = default;
    Stratum(double a0, double a1, double e0, double e1, std::uint64_t k)
        : a_lo(a0), a_hi(a1), a_c(0.5 * (a0 + a1)), e_lo(e0), e_hi(e1), e_mid(0.5 * (e0 + e1)),
          e_top_c(0.25 * e0 + 0.75 * e1), e_bottom_c(0.75 * e0 + 0.25 * e1), key(k) {}
    /// The mirror of (a, e) about the stratum's centre.
    std::pair<double, double> mirror(double a, double e) const {
        return {a_lo.rad + a_hi.rad - a, e_lo.rad + e_hi.rad - e};
    }
};

struct BeamRays {
    std::vector<Stratum> strata;
    std::vector<Ray> rays;
    std::uint32_t add(double a, double e) {
        rays.push_back({Angle(a), Angle(e), false, false, {}});
        return std::uint32_t(rays.size() - 1);
    }
    /// Adds both antithetic pairs of stratum st (drawn from its key).
    void fill(Stratum& st) {
        for (int pair = 0; pair < 2; ++pair) {
            const auto [ua, ue] = jitter(st.key, pair);
            const double a = st.a_lo.rad + ua * (st.a_hi.rad - st.a_lo.rad);
            const double e = st.e_lo.rad + ue * (st.e_hi.rad - st.e_lo.rad);
            const auto [ma, me] = st.mirror(a, e);
            st.ray[2 * pair] = add(a, e), st.ray[2 * pair + 1] = add(ma, me);
        }
    }
};

class JitteredSampler {
  public:
    JitteredSampler(const SceneGeometry& g, const SceneDesc& s, const TraceControl& control)
        : g_(g), s_(s), control_(control), frame_(s), multipath_(detail::multipath_active(s)),
          mp_(g, s, frame_), beams_(size_t(s.sonar.beams)) {
        for (int i = 0; i < s.sonar.beams; ++i)
            if (control.traces(i)) traced_.push_back(i);
        stride_ = std::max(1, int(traced_.size()) / kEstimateBeams);
        for (size_t k = 0; k < traced_.size(); k += size_t(stride_)) {
            groups_.emplace_back(traced_.begin() + long(k),
                                 traced_.begin() + long(std::min(traced_.size(), k + size_t(stride_))));
        }
    }

    TraceResult run() {
        base();
        TraceResult::ErrorEstimate est;
        int passes = 1;
        bool budget_short = false;
        std::vector<char> changed(groups_.size(), 1);
        BinErrors all;
        while (!control_.preview) {
            update_errors(all, changed);
            est = summarise({&all});
            if (!est.valid || est.meets(s_.sampling) || passes >= kMaxPasses) break;
            std::vector<std::vector<char>> marks;
            const auto chosen = choose_regions(all);
            if (chosen.empty()) break;
            const std::uint64_t added = mark_strata(chosen, marks, changed, budget_short);
            if (added == 0) break;
            split_and_trace(marks);
            ++passes;
        }
        TraceResult out = cells();
        est.passes = passes;
        est.budget_reached = budget_short;
        out.error_estimate = est;
        return out;
    }

  private:
    const SceneGeometry& g_;
    const SceneDesc& s_;
    const TraceControl& control_;
    detail::RayFrame frame_;
    bool multipath_;
    detail::Multipath mp_;
    std::vector<BeamRays> beams_;
    std::vector<int> traced_;
    std::vector<std::vector<int>> groups_; ///< the first beam of each is its sample beam
    int stride_ = 1;
    std::uint64_t rays_ = 0;
    double ref_db_ = std::numeric_limits<double>::quiet_NaN();

    void check_cancel() const {
        if (control_.cancelled()) throw TraceCancelled();
    }

    /// Traces every ray of every beam not traced yet.
    void trace_new() {
        tbb::parallel_for(0, int(traced_.size()), [&](int k) {
            if (control_.cancelled()) return;
            for (Ray& r : beams_[size_t(traced_[size_t(k)])].rays) {
                if (r.traced) continue;
                r.traced = true;
                if (auto h = detail::first_hit(g_, s_, frame_.origin, frame_.dir(r.a, r.e), frame_.t_max))
                    r.hit = true, r.h = *h;
            }
        });
        check_cancel();
    }

    void base() {
        const int K = s_.sampling.azimuth_rays, M = s_.sampling.elevation_rays;
        const SonarGrid& grid = *frame_.grid;
        const double phi = frame_.elevation_weight.traced_fov_rad(), de = phi / M;
        for (int i : traced_) {
            BeamRays& b = beams_[size_t(i)];
            b.strata.reserve(size_t(K) * M * 2), b.rays.reserve(size_t(4) * K * M * 2);
            const double a0 = grid.beam_starboard_edge_rad(i), da = grid.beam_width_rad(i) / K;
            for (int k = 0; k < K; ++k)
                for (int j = 0; j < M; ++j) {
                    const double e_hi = phi / 2 - j * de;
                    Stratum st(a0 + k * da, a0 + (k + 1) * da, e_hi - de, e_hi,
                               mix(mix(mix(std::uint64_t(i) + 0x51ull) ^ std::uint64_t(k)) ^ std::uint64_t(j)));
                    b.fill(st);
                    b.strata.push_back(st);
                }
        }
        rays_ = std::uint64_t(traced_.size()) * 4 * K * M;
        trace_new();
    }

    /// Ray r's cell: the half of its stratum it falls in (whole: the whole stratum), at its share of the
    /// solid angle; `pair`: 0 or 1.
    Cell cell_of(const Ray& r, const Stratum& st, int pair, bool whole) const {
        const bool top = r.e.rad >= st.e_mid.rad;
        const Angle& lo = whole || !top ? st.e_lo : st.e_mid;
        const Angle& hi = whole || top ? st.e_hi : st.e_mid;
        const std::pair<Angle, Angle> centre{st.a_c, whole ? st.e_mid : top ? st.e_top_c : st.e_bottom_c};
        Cell c = detail::make_cell(frame_, r.h, r.a, r.e, st.a_lo, st.a_hi, lo, hi, &centre);
        c.solid_angle_sr *= whole ? 0.25f : 0.5f; // four rays per stratum; two per half of it
        c.azimuth_rad = float(st.a_c.rad);        // the stratum's: the cell's azimuth extent
        c.half = std::uint8_t(pair);
        return c;
    }

    /// Beam i's cells, fine (each ray's half stratum) or whole.
    std::vector<Cell> beam_cells(int i, bool whole) const {
        const BeamRays& b = beams_[size_t(i)];
        std::vector<Cell> out;
        out.reserve(b.rays.size());
        for (const Stratum& st : b.strata)
            for (int q = 0; q < 4; ++q) {
                const Ray& r = b.rays[st.ray[q]];
                if (r.hit) out.push_back(cell_of(r, st, q >> 1, whole));
            }
        return out;
    }

    /// Recomputes the bin errors of the groups marked changed (all's columns: one per group).
    void update_errors(BinErrors& all, std::vector<char>& changed) {
        std::vector<size_t> idx;
        for (size_t k = 0; k < groups_.size(); ++k)
            if (changed[k]) idx.push_back(k);
        if (idx.empty()) return;
        TraceResult sample;
        sample.beams = int(idx.size());
        sample.cells.resize(idx.size());
        std::vector<std::vector<Cell>> coarse(idx.size());
        tbb::parallel_for(0, int(idx.size()), [&](int n) {
            const int i = groups_[idx[size_t(n)]].front();
            sample.cells[size_t(n)] = beam_cells(i, false), coarse[size_t(n)] = beam_cells(i, true);
        });
        const BinErrors e = bin_errors(sample, coarse, s_, ref_db_);
        if (std::isnan(ref_db_)) ref_db_ = e.ref_db;
        if (all.beams == 0) {
            all.bins = e.bins, all.beams = int(groups_.size()), all.ref_db = e.ref_db;
            const size_t m = size_t(all.bins) * size_t(all.beams);
            all.level.assign(m, 0), all.error.assign(m, 0), all.variance.assign(m, 0), all.footprint.assign(m, 0);
        }
        for (size_t n = 0; n < idx.size(); ++n)
            for (int b = 0; b < e.bins; ++b) {
                const size_t from = size_t(b) * idx.size() + n, to = size_t(b) * size_t(all.beams) + idx[n];
                all.level[to] = e.level[from], all.error[to] = e.error[from];
                all.variance[to] = e.variance[from], all.footprint[to] = e.footprint[from];
            }
        std::fill(changed.begin(), changed.end(), 0);
    }

    struct Region {
        size_t group;
        int band;
        double num = 0, excess = 0;
    };

    /// The regions (group, range band) to refine, largest shares first, until what is left would meet both
    /// tolerances times kAim.
    std::vector<Region> choose_regions(const BinErrors& all) const {
        const int bins = all.bins, per_band = std::max(1, (bins + kBands - 1) / kBands);
        std::vector<Region> regions;
        double num = 0, den = 0, echoing = 0, excess = 0;
        const double lim = std::pow(10.0, s_.sampling.tolerance_db / 10) - 1; // error / level at tolerance_db
        for (size_t k = 0; k < groups_.size(); ++k)
            for (int q = 0; q * per_band < bins; ++q) {
                Region r{k, q};
                for (int b = q * per_band; b < std::min(bins, (q + 1) * per_band); ++b) {
                    const size_t c = size_t(b) * size_t(all.beams) + k;
                    r.num += all.error[c], den += all.level[c];
                    if (all.level[c] > 0) echoing += 1, r.excess += all.error[c] > lim * all.level[c];
                }
                num += r.num, excess += r.excess;
                if (r.num > 0) regions.push_back(r);
            }
        const double num_aim = kAim * s_.sampling.tolerance_rel_l1 * den, excess_aim = kAim * 0.5 * echoing;
        std::vector<char> taken(regions.size(), 0);
        std::vector<size_t> order(regions.size());
        std::iota(order.begin(), order.end(), size_t(0));
        std::stable_sort(order.begin(), order.end(),
                         [&](size_t a, size_t b) { return regions[a].num > regions[b].num; });
        for (size_t o : order) {
            if (num <= num_aim) break;
            taken[o] = 1, num -= (1 - kRefinedShare) * regions[o].num;
            excess -= (1 - kRefinedShare) * regions[o].excess;
        }
        std::stable_sort(order.begin(), order.end(),
                         [&](size_t a, size_t b) { return regions[a].excess > regions[b].excess; });
        for (size_t o : order) {
            if (excess <= excess_aim) break;
            if (taken[o]) continue;
            taken[o] = 1, excess -= (1 - kRefinedShare) * regions[o].excess;
        }
        std::vector<Region> out;
        for (size_t o = 0; o < regions.size(); ++o)
            if (taken[o]) out.push_back(regions[o]);
        return out;
    }

    /// Marks, per beam of the chosen regions' groups, the strata whose rays reach the region's range band
    /// (marks[beam][stratum]), within the ray budget (regions in the order given); returns the rays the
    /// splits add and flags the groups that change.
    std::uint64_t mark_strata(const std::vector<Region>& chosen, std::vector<std::vector<char>>& marks,
                              std::vector<char>& changed, bool& budget_short) {
        const SonarGrid& grid = *frame_.grid;
        const int bins = s_.sonar.range_bins, per_band = std::max(1, (bins + kBands - 1) / kBands);
        marks.assign(beams_.size(), {});
        std::uint64_t added = 0;
        const std::uint64_t budget = std::uint64_t(s_.sampling.max_rays);
        for (const Region& r : chosen) {
            const double r0 = grid.bin_near_edge_m(r.band * per_band);
            const double r1 = grid.bin_near_edge_m(std::min(bins, (r.band + 1) * per_band));
            std::uint64_t cost = 0;
            std::vector<std::pair<int, size_t>> these;
            for (int i : groups_[r.group]) {
                const BeamRays& b = beams_[size_t(i)];
                auto& m = marks[size_t(i)];
                if (m.empty()) m.assign(b.strata.size(), 0);
                for (size_t n = 0; n < b.strata.size(); ++n) {
                    if (m[n]) continue;
                    double lo = INFINITY, hi = -INFINITY;
                    for (std::uint32_t q : b.strata[n].ray)
                        if (b.rays[q].hit) lo = std::min(lo, b.rays[q].h.t), hi = std::max(hi, b.rays[q].h.t);
                    // The rays span the stratum; its footprint reaches about as far again beyond them.
                    const double pad = 0.5 * (hi - lo);
                    if (lo - pad <= r1 && hi + pad >= r0) these.push_back({i, n}), cost += 4;
                }
            }
            if (rays_ + added + cost > budget) {
                budget_short = true;
                continue;
            }
            for (auto [i, n] : these) marks[size_t(i)][n] = 1;
            added += cost;
            if (cost) changed[r.group] = 1;
        }
        rays_ += added;
        return added;
    }

    /// Splits the marked strata in two (along the longer side on the surface) and traces the new rays.
    void split_and_trace(const std::vector<std::vector<char>>& marks) {
        tbb::parallel_for(0, int(traced_.size()), [&](int k) {
            const int i = traced_[size_t(k)];
            const auto& m = marks[size_t(i)];
            if (m.empty()) return;
            BeamRays& b = beams_[size_t(i)];
            const size_t n0 = b.strata.size();
            for (size_t n = 0; n < n0; ++n)
                if (m[n]) split(b, n);
        });
        trace_new();
    }

    /// Whether stratum st is longer on the surface in elevation than in azimuth (at its rays' mean range and
    /// incidence).
    bool split_in_elevation(const BeamRays& b, const Stratum& st) const {
        double cos_sum = 0;
        int hits = 0;
        for (std::uint32_t q : st.ray) {
            const Ray& r = b.rays[q];
            if (!r.hit) continue;
            cos_sum += std::abs(glm::dot(r.h.face_normal, frame_.dir(r.a, r.e))), ++hits;
        }
        const double de = st.e_hi.rad - st.e_lo.rad, da = (st.a_hi.rad - st.a_lo.rad) * st.e_mid.c;
        if (hits == 0) return de >= da;
        return de / std::max(kMinCosIncidence, cos_sum / hits) >= da;
    }

    /// Stratum n becomes its first child, the second is appended; each keeps the old rays that fell in it
    /// and gets their mirrors.
    void split(BeamRays& b, size_t n) {
        const Stratum st = b.strata[n];
        const bool elevation = split_in_elevation(b, st);
        Stratum child[2];
        if (elevation) {
            child[0] = Stratum(st.a_lo.rad, st.a_hi.rad, st.e_mid.rad, st.e_hi.rad, mix(st.key ^ 1));
            child[1] = Stratum(st.a_lo.rad, st.a_hi.rad, st.e_lo.rad, st.e_mid.rad, mix(st.key ^ 2));
        } else {
            child[0] = Stratum(st.a_lo.rad, st.a_c.rad, st.e_lo.rad, st.e_hi.rad, mix(st.key ^ 3));
            child[1] = Stratum(st.a_c.rad, st.a_hi.rad, st.e_lo.rad, st.e_hi.rad, mix(st.key ^ 4));
        }
        for (int pair = 0; pair < 2; ++pair)
            for (int q = 2 * pair; q < 2 * pair + 2; ++q) {
                const std::uint32_t id = st.ray[q];
                const Ray& r = b.rays[id];
                const bool first = elevation ? r.e.rad >= st.e_mid.rad : r.a.rad < st.a_c.rad;
                Stratum& c = child[first ? 0 : 1];
                const auto [ma, me] = c.mirror(r.a.rad, r.e.rad);
                c.ray[2 * pair] = id, c.ray[2 * pair + 1] = b.add(ma, me); // r's reference may move here
            }
        b.strata[n] = child[0];
        b.strata.push_back(child[1]);
    }

    /// The final cells of every beam (and their ghosts), and the sample beams' whole-stratum cells.
    TraceResult cells() {
        TraceResult out;
        out.beams = s_.sonar.beams;
        out.halves = true;
        out.cells.resize(size_t(out.beams));
        out.coarse_cells.resize(size_t(out.beams));
        out.estimate_stride = stride_;
        std::vector<std::vector<GhostCell>> ghosts(multipath_ ? size_t(out.beams) : 0);
        std::vector<std::uint64_t> ghost_rays(size_t(out.beams), 0);
        tbb::parallel_for(0, int(traced_.size()), [&](int k) {
            const int i = traced_[size_t(k)];
            out.cells[size_t(i)] = beam_cells(i, false);
            if (k % stride_ == 0) out.coarse_cells[size_t(i)] = beam_cells(i, true);
            if (!multipath_) return;
            const BeamRays& b = beams_[size_t(i)];
            for (const Stratum& st : b.strata)
                for (int q = 0; q < 4; ++q) {
                    const Ray& r = b.rays[st.ray[q]];
                    if (!r.hit) continue;
                    const bool top = r.e.rad >= st.e_mid.rad;
                    auto& gs = ghosts[size_t(i)];
                    const size_t before = gs.size();
                    ghost_rays[size_t(i)] += mp_.ghosts(r.h, r.a, r.e, st.a_lo, st.a_hi, top ? st.e_mid : st.e_lo,
                                                        top ? st.e_hi : st.e_mid, i, gs);
                    for (size_t n = before; n < gs.size(); ++n)
                        gs[n].cell.solid_angle_sr *= 0.5f, gs[n].cell.half = std::uint8_t(q >> 1);
                }
        });
        check_cancel();
        out.rays_traced = rays_;
        if (multipath_) {
            out.ghosts = detail::gather_ghosts(ghosts, s_);
            for (auto r : ghost_rays) out.multipath_rays += r;
        }
        out.preview = control_.preview;
        return out;
    }
};

} // namespace

TraceResult trace_jittered(const SceneGeometry& g, const SceneDesc& s, const TraceControl& control) {
    return JitteredSampler(g, s, control).run();
}

} // namespace sonarsim

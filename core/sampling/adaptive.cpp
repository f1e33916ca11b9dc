// Adaptive sampling: refine where the integrand of SONAR_MODEL.md is not smooth and the error that leaves
// in the image is significant against the tolerance; leave the rest coarse (see core/sampling/README.md).
// This file holds the passes. The image's traced beams form groups (every kEstimateStride-th beam of a wide
// image is a group's sample, whose error is estimated). A pass traces some groups at one base grid and
// refines them (adaptive_pass.cpp); a group whose base grid alone misses the tolerances by a large share is
// left for a denser one (x3) at once. When the estimate misses sampling.tolerance_db or tolerance_rel_l1,
// the groups with the largest estimated shares of the error go to a denser base grid, largest first, until
// the others would meet both; the rest keep their cells. Passes stop when the estimate meets both, at
// kMaxPasses base grids or at the ray budget.
#include "core/sampling/adaptive_sampler.hpp"

#include "core/scene/params.hpp"
#include "core/shading/accumulate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace sonarsim {
namespace {

using adaptive::BeamGroups;
using adaptive::columns_of;
using adaptive::SampleError;
using adaptive::Sampler;

/// Base grids: elevation_rays x 3^level, level < kMaxPasses.
constexpr int kMaxLevel = adaptive::kMaxPasses - 1;
/// A group taken to a denser base grid is taken to keep this share of its error (first order).
constexpr double kRefinedShare = 1.0 / 3;
/// The groups taken after an estimate aim at this fraction of each tolerance, so that one more pass is
/// rarely needed.
constexpr double kAim = 0.75;
/// A pass whose base grid times this is more than the budget has left is ordered from the start: refinement
/// adds up to about 2-4 times a pass's base grid where the budget does not bind, so such a pass would likely
/// be refused first come and traced twice.
constexpr double kLikelyRefinement = 8;

struct Choice {
    std::vector<char> take;    ///< per group
    bool budget_short = false; ///< a group was wanted that the budget could not pay for
};

/// Groups to take to a denser base grid, the largest estimated shares of the error first, until what is
/// left meets both tolerances times `aim` (a group taken keeps kRefinedShare of its share). errs[g]: group
/// g's share (null: none); cost[g]: the rays its denser base grid takes (negative: not eligible).
Choice choose(const SceneDesc& s, const std::vector<const SampleError*>& errs,
              const std::vector<double>& cost, double budget_left, double aim) {
    const size_t G = errs.size();
    Choice c;
    c.take.assign(G, 0);
    double num = 0, den = 0, n = 0, excess = 0;
    std::vector<double> ex(G, 0.0);
    const float lim = float(2 * s.sampling.tolerance_db); // estimates are half the difference
    for (size_t g = 0; g < G; ++g) {
        if (!errs[g]) continue;
        num += errs[g]->share(), den += errs[g]->den, n += double(errs[g]->diffs_db.size());
        for (float d : errs[g]->diffs_db) ex[g] += d > lim;
        excess += ex[g];
    }
    if (!(den > 0)) return c;
    const double num_aim = 2 * aim * s.sampling.tolerance_rel_l1 * den;
    const double excess_aim = aim * 0.5 * n; // the median meets the tolerance below half the bins
    auto take = [&](size_t g) {
        if (c.take[g] || !errs[g] || cost[g] < 0) return;
        if (cost[g] > budget_left) {
            c.budget_short = true;
            return;
        }
        budget_left -= cost[g];
        c.take[g] = 1;
        num -= (1 - kRefinedShare) * errs[g]->share();
        excess -= (1 - kRefinedShare) * ex[g];
    };
    std::vector<size_t> order(G);
    std::iota(order.begin(), order.end(), size_t(0));
    auto share = [&](size_t g) { return errs[g] ? errs[g]->share() : 0.0; };
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return share(a) > share(b); });
    for (size_t g : order) {
        if (num <= num_aim) break;
        take(g);
    }
    if (excess > excess_aim) {
        std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return ex[a] > ex[b]; });
        for (size_t g : order) {
            if (excess <= excess_aim) break;
            take(g);
        }
    }
    return c;
}

/// The traced beams in groups of `stride` (adaptive::BeamGroups).
BeamGroups make_groups(const std::vector<int>& traced, int stride) {
    BeamGroups groups;
    for (size_t k = 0; k < traced.size(); k += size_t(stride))
        groups.emplace_back(traced.begin() + long(k),
                            traced.begin() + long(std::min(traced.size(), k + size_t(stride))));
    return groups;
}

} // namespace

TraceResult trace_adaptive(const SceneGeometry& g, const SceneDesc& s, const TraceControl& control,
                           ImagePass* caller_pass) {
    Sampler sp(g, s, control);
    sp.ordered = control.ordered_budget;
    const int N = s.sonar.beams, T = int(sp.traced.size());
    const int stride = sp.multipath                         ? 1
                       : T >= adaptive::kWideBeams          ? adaptive::kWideEstimateStride
                       : T >= 8 * adaptive::kEstimateStride ? adaptive::kEstimateStride
                                                            : 1;
    const BeamGroups groups = make_groups(sp.traced, stride);
    const size_t G = groups.size();
    std::vector<int> level(G, 0);
    std::vector<char> pending(G, 1), has_err(G, 0);
    std::vector<SampleError> err(G);
    std::vector<int> az_mult(G, 1); // a group's columns per beam, in multiples of azimuth_rays (strict)
    if (sp.strict) sp.column_mult.assign(size_t(N), 1);
    TraceResult out;
    out.beams = N;
    out.cells.resize(size_t(N));
    out.preview = control.preview;
    std::uint64_t rays = 0, multipath_rays = 0;
    ImagePass own_pass;
    ImagePass& whole = caller_pass ? *caller_pass : own_pass; // the whole image, when pass 1 traced all of it
    whole.forget();
    TraceResult::ErrorEstimate est;
    adaptive::Beams carried; // bumped groups' base grids, split into the next pass's
    // What each group's last estimate was made from (beside its fine cells), for reestimate_error, when
    // the caller may keep the placement (the multipath tank's are twice its hits).
    const bool keep_cells = control.keep_placement && !control.preview;
    auto kept = std::make_shared<AdaptiveEstimateCells>();
    kept->samples.assign(G, -1);
    for (TraceResult* r : {&kept->coarse, &kept->coarse_edges, &kept->az_one, &kept->az_three}) {
        r->beams = int(G);
        r->cells.resize(G);
        if (sp.multipath) r->ghosts.resize(G);
    }
    auto M0_of = [&](int L) { return s.sampling.elevation_rays * int(std::lround(std::pow(3.0, L))); };
    // A denser base grid exists (levels, and the image's limit on rays).
    auto denser = [&](int L) { return L < kMaxLevel && sp.base_rays(M0_of(L + 1)) <= kMaxRaysPerImage / 9; };
    auto budget_left = [&] { return double(s.sampling.max_rays) - double(sp.rays.load()); };
    // The rays of group g's base grid one level denser (negative: none).
    auto next_cost = [&](size_t g) {
        return denser(level[g]) ? sp.base_rays(M0_of(level[g] + 1), int(groups[g].size())) * az_mult[g]
                                : -1.0;
    };
    // Strict: whether group g's next step is three columns per beam (azimuth the larger share of its error).
    auto azimuth_next = [&](size_t g) { return az_mult[g] == 1 && 2 * err[g].az_num > err[g].num; };
    int passes = 0; // base grids traced (trace_pass calls)
    for (int pass = 1;; ++pass) {
        for (int L = 0; L <= kMaxLevel; ++L) {
            std::vector<size_t> idx; // the groups of this base grid
            BeamGroups sel;
            for (size_t k = 0; k < G; ++k)
                if (pending[k] && level[k] == L) idx.push_back(k), sel.push_back(groups[k]);
            if (sel.empty()) continue;
            // A base grid far off goes denser at once, the largest shares first (the others' shares as last
            // estimated), unrefined here.
            adaptive::BumpRule bump = [&](const std::vector<SampleError>& base) {
                std::vector<const SampleError*> e(G, nullptr);
                std::vector<double> cost(G, -1.0);
                for (size_t k = 0; k < G; ++k)
                    if (has_err[k] && !(pending[k] && level[k] == L)) e[k] = &err[k];
                for (size_t k = 0; k < idx.size(); ++k)
                    e[idx[k]] = &base[k], cost[idx[k]] = next_cost(idx[k]);
                const Choice c = choose(s, e, cost, budget_left(), adaptive::kSkipFactor);
                std::vector<char> out_k(idx.size(), 0);
                for (size_t k = 0; k < idx.size(); ++k) out_k[k] = c.take[idx[k]];
                return out_k;
            };
            const bool may_bump = denser(L) && !control.preview && !sp.multipath;
            ++passes;
            // First come is faster (each column refined while in the cache), but where the budget refuses a
            // ray, which rays it paid for depends on the threads: such a pass is traced again from where it
            // started with the budget paid in a fixed order, so that the same scene gives the same bytes.
            // The passes before it were not refused, so they are what an ordered pass would have made. A
            // pass likely to reach the budget is ordered from the start.
            double base = 0;
            for (size_t k : idx) base += sp.base_rays(M0_of(L), int(groups[k].size())) * az_mult[k];
            if (kLikelyRefinement * base > budget_left()) sp.ordered = true;
            const std::uint64_t rays_before = sp.rays.load();
            const adaptive::Beams carried_before = sp.ordered ? adaptive::Beams{} : carried;
            adaptive::PassCells pc =
                adaptive::trace_pass(sp, M0_of(L), sel, may_bump ? &bump : nullptr, &carried);
            if (!sp.ordered && sp.budget_hit.load()) {
                pc = adaptive::PassCells{}; // its memory back first
                carried = carried_before;
                sp.rays.store(rays_before), sp.budget_hit.store(false);
                sp.ordered = true; // the same pass (passes counts it once, as an ordered trace does)
                pc = adaptive::trace_pass(sp, M0_of(L), sel, may_bump ? &bump : nullptr, &carried);
            }
            rays += pc.fine.rays_traced;
            multipath_rays += pc.fine.multipath_rays;
            if (sp.multipath) out.ghosts = std::move(pc.fine.ghosts);
            std::vector<int> samples(idx.size(), -1); // refined groups' sample beams, by slot
            bool all = pass == 1 && idx.size() == G;
            for (size_t k = 0; k < idx.size(); ++k) {
                if (pc.bumped[k]) {
                    level[idx[k]] = L + 1, all = false;
                    continue;
                }
                pending[idx[k]] = 0;
                for (int i : sel[k]) out.cells[size_t(i)] = std::move(pc.fine.cells[size_t(i)]);
                samples[k] = sel[k].front();
            }
            if (control.preview) continue;
            if (std::all_of(samples.begin(), samples.end(), [](int i) { return i < 0; }))
                continue; // every group went denser: none refined here, nothing to estimate
            // The estimate's shares of the groups refined here: their sample beams, fine and coarse.
            PolarImage fine_img;
            if (all) { // the whole image in one pass: shade it once, for the estimate and the caller
                fine_img = columns_of(*whole.run(out, s).image, samples);
            } else {
                fine_img = adaptive::shade_beams(out, s, samples);
            }
            sp.set_ref_db(fine_img);
            const int sampled = int(idx.size());
            const PolarImage edges_img = shade_columns(pc.coarse_edges, s, sampled);
            PolarImage az_one, az_three;
            const bool probed = !pc.az_one.cells.empty();
            if (probed)
                az_one = shade_columns(pc.az_one, s, sampled),
                az_three = shade_columns(pc.az_three, s, sampled);
            std::vector<SampleError> shares =
                adaptive::sample_errors(shade_columns(pc.coarse, s, sampled), fine_img, sp.ref_db,
                                        {&edges_img, probed ? &az_one : nullptr, probed ? &az_three : nullptr,
                                         sp.strict, sp.probe_every});
            for (size_t k = 0; k < idx.size(); ++k)
                if (samples[k] >= 0) err[idx[k]] = std::move(shares[k]), has_err[idx[k]] = 1;
            for (size_t k = 0; k < idx.size() && keep_cells; ++k) {
                if (samples[k] < 0) continue;
                kept->samples[idx[k]] = samples[k];
                auto keep = [&](TraceResult& from, TraceResult& to) { // an unprobed pass leaves it empty
                    to.cells[idx[k]] = k < from.cells.size() ? std::move(from.cells[k]) : std::vector<Cell>{};
                    if (sp.multipath)
                        to.ghosts[idx[k]] =
                            k < from.ghosts.size() ? std::move(from.ghosts[k]) : std::vector<GhostCell>{};
                };
                keep(pc.coarse, kept->coarse), keep(pc.coarse_edges, kept->coarse_edges);
                keep(pc.az_one, kept->az_one), keep(pc.az_three, kept->az_three);
                kept->probed = kept->probed || probed;
            }
        }
        if (control.cancelled()) throw TraceCancelled();
        if (control.preview) break;
        if (std::find(pending.begin(), pending.end(), 1) != pending.end()) continue; // bumped groups
        std::vector<const SampleError*> e(G);
        for (size_t k = 0; k < G; ++k) e[k] = &err[k];
        est = adaptive::combine_errors(e);
        est.passes = passes;
        if (est.meets(s.sampling)) break;
        // Each group's next step: three columns per beam (strict, azimuth its larger share) or a denser base
        // grid. Multipath: every group the same way (its images' ghosts are the whole image's, so every
        // pass after the first traces every group), three columns when azimuth is the larger share overall.
        std::vector<char> az(G);
        for (size_t k = 0; k < G; ++k) az[k] = azimuth_next(k);
        if (sp.multipath) {
            double az_sum = 0, sum = 0;
            for (size_t k = 0; k < G; ++k) az_sum += 2 * err[k].az_num, sum += err[k].num;
            const bool all_az =
                std::all_of(az_mult.begin(), az_mult.end(), [](int m) { return m == 1; }) && az_sum > sum;
            std::fill(az.begin(), az.end(), char(all_az));
        }
        std::vector<double> cost(G);
        for (size_t k = 0; k < G; ++k) // three columns re-trace the group's base grid
            cost[k] = az[k] ? 3 * sp.base_rays(M0_of(level[k]), int(groups[k].size())) : next_cost(k);
        Choice c = choose(s, e, cost, budget_left(), kAim);
        // Multipath: every group or none.
        if (sp.multipath && std::find(c.take.begin(), c.take.end(), 1) != c.take.end())
            for (size_t k = 0; k < G; ++k) c.take[k] = cost[k] >= 0;
        bool any = false;
        for (size_t k = 0; k < G; ++k) {
            if (!c.take[k]) continue;
            pending[k] = 1, any = true;
            if (az[k]) {
                // Strict: azimuth is the larger share, so three columns per beam at the same base grid (their
                // coarse image merges them, and the azimuth probe goes on with thirds of the new columns).
                az_mult[k] = 3;
                for (int i : groups[k]) sp.column_mult[size_t(i)] = 3;
            } else {
                ++level[k];
            }
        }
        if (!any) {
            est.budget_reached = c.budget_short;
            break;
        }
        whole.forget(); // the image changes
    }
    est.budget_reached = est.budget_reached || sp.budget_hit.load();
    est.strict = sp.strict;
    if (!sp.strict && est.valid) { // fast reports what its probe saw as well (it stopped without it)
        std::vector<const SampleError*> e(G);
        for (size_t k = 0; k < G; ++k) e[k] = &err[k];
        const auto seen = adaptive::combine_errors(e, true);
        est.rel_l1 = seen.rel_l1, est.median_abs_db = seen.median_abs_db, est.p95_abs_db = seen.p95_abs_db;
        est.azimuth_rel_l1 = seen.azimuth_rel_l1;
    }
    if (!control.preview) out.error_estimate = est;
    if (keep_cells && est.valid) {
        kept->ref_db = sp.ref_db, kept->probe_every = sp.probe_every;
        out.estimate_cells = std::move(kept);
    }
    out.rays_traced = rays;
    out.multipath_rays = multipath_rays;
    return out;
}

} // namespace sonarsim

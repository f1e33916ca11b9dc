// Adaptive sampling: refine where the integrand of SONAR_MODEL.md is not smooth and the error that leaves
// in the image is significant against the tolerance; leave the rest coarse (see core/ARCHITECTURE.md).
// This file holds the passes: each pass (adaptive_pass.cpp) triples the base grid until the estimated error
// meets sampling.tolerance_db, kMaxPasses are done or the ray budget would be exceeded.
#include "core/sampling/adaptive_sampler.hpp"

#include "core/scene/params.hpp"

namespace sonarsim {
namespace {

using adaptive::Sampler;

/// Both targets: the estimated median |dB| (tolerance_db) and the estimated rel L1 (tolerance_rel_l1).
bool tolerance_met(const SceneDesc& s, const TraceResult::ErrorEstimate& est) {
    return est.median_abs_db <= s.sampling.tolerance_db && est.rel_l1 <= s.sampling.tolerance_rel_l1;
}

/// Rays of the base grid of the pass after one at M0.
double next_base_rays(const Sampler& sp, int M0) {
    return sp.base_rays(3 * M0);
}

/// Whether a pass at M0 can be followed by a denser one (passes left, the budget and the image's limit).
bool next_pass_fits(const Sampler& sp, int pass, int M0) {
    const double next_base = next_base_rays(sp, M0);
    // What this pass refines comes out of the budget too: keep the next base grid's rays free.
    return pass < adaptive::kMaxPasses && next_base <= kMaxRaysPerImage / 9 &&
           double(sp.rays.load()) + sp.base_rays(M0) + next_base <= double(sp.s.sampling.max_rays);
}

/// Whether another pass (base grid M0 x 3) is not to be made; sets est.budget_reached when only the budget
/// stops it.
bool last_pass(const Sampler& sp, const TraceResult& out, TraceResult::ErrorEstimate& est, int pass, int M0) {
    const SceneDesc& s = sp.s;
    // A denser base grid must fit in what is left of the budget.
    const double next_base = next_base_rays(sp, M0);
    const bool over_budget = double(sp.rays.load()) + next_base > double(s.sampling.max_rays);
    const bool met = tolerance_met(s, est);
    if (!(out.preview || met || pass == adaptive::kMaxPasses || est.budget_reached ||
          next_base > kMaxRaysPerImage / 9 || over_budget))
        return false;
    if (!out.preview && !met && !est.budget_reached && pass < adaptive::kMaxPasses && over_budget)
        est.budget_reached = true; // the next pass would not fit
    return true;
}

} // namespace

TraceResult trace_adaptive(const SceneGeometry& g, const SceneDesc& s, const TraceControl& control) {
    Sampler sp(g, s, control);
    std::uint64_t rays = 0, multipath_rays = 0;
    int M0 = s.sampling.elevation_rays;
    TraceResult out;
    for (int pass = 1;; ++pass) {
        TraceResult::ErrorEstimate est;
        bool skipped = false;
        // Asked before the pass traces: it counts this pass's base grid and the next one's.
        const bool may_skip = next_pass_fits(sp, pass, M0);
        TraceResult r = adaptive::trace_pass(sp, M0, est, may_skip, skipped);
        rays += r.rays_traced;
        multipath_rays += r.multipath_rays;
        sp.edge_azimuth_levels = 1; // passes after the first: see Sampler::edge_azimuth_levels
        if (skipped) {              // the base grid alone was far off: a denser one, unrefined here
            M0 *= 3;
            continue;
        }
        out = std::move(r);
        est.passes = pass;
        est.budget_reached = sp.budget_hit.load();
        const bool done = last_pass(sp, out, est, pass, M0);
        out.error_estimate = est;
        if (done) break;
        M0 *= 3;
    }
    out.rays_traced = rays;
    out.multipath_rays = multipath_rays;
    return out;
}

} // namespace sonarsim

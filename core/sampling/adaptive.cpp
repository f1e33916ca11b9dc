// Adaptive sampling: refine where the integrand of SONAR_MODEL.md is not smooth and the error that leaves
// in the image is significant against the tolerance; leave the rest coarse (see core/ARCHITECTURE.md).
// This file holds the passes: each pass (adaptive_pass.cpp) triples the base grid until the estimated error
// meets sampling.tolerance_db, kMaxPasses are done or the ray budget would be exceeded.
#include "core/sampling/adaptive_sampler.hpp"

#include "core/scene/params.hpp"

namespace sonarsim {
namespace {

using adaptive::Sampler;

/// Whether another pass (base grid M0 x 3) is not to be made; sets est.budget_reached when only the budget
/// stops it.
bool last_pass(const Sampler& sp, const TraceResult& out, TraceResult::ErrorEstimate& est, int pass, int M0) {
    const SceneDesc& s = sp.s;
    // A denser base grid must fit in what is left of the budget.
    const double next_base = double(M0) * 3 * s.sonar.beams * s.sampling.azimuth_rays;
    const bool over_budget = double(sp.rays.load()) + next_base > double(s.sampling.max_rays);
    const bool met = est.median_abs_db <= s.sampling.tolerance_db;
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
        out = adaptive::trace_pass(sp, M0, est);
        rays += out.rays_traced;
        multipath_rays += out.multipath_rays;
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

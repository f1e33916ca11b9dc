// Adaptive sampling: the error estimate, per group of beams and for the whole image. Each group's sample
// beam is shaded twice, from its cells and from the same cells one level coarser; the image's estimate is
// the relative L1 and the |dB| quantiles of their difference over all samples, halved (adaptive_sampler.hpp).
#include "core/sampling/adaptive_sampler.hpp"

#include "core/shading/accumulate.hpp"
#include "core/sampling/trace.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace sonarsim::adaptive {

std::vector<SampleError> sample_errors(const PolarImage& coarse, const PolarImage& fine, double ref_db,
                                       const EstimateImages& images) {
    const int N = fine.beams, K = fine.bins;
    if (std::isnan(ref_db)) ref_db = 0; // no echo estimated yet: any fixed level does
    auto linear = [&](float v) { return v > -INFINITY ? std::exp((double(v) - ref_db) * kLn10Over10) : 0.0; };
    const PolarImage *edges = images.coarse_edges, *one = images.az_one, *three = images.az_three;
    const bool acts = images.act_on_azimuth;
    std::vector<SampleError> out(static_cast<size_t>(N));
    const bool report = !acts && one && three; // fast: the probe's share is reported, not acted on
    tbb::parallel_for(0, N, [&](int i) {       // each sample beam's sums are its own
        SampleError& e = out[size_t(i)];
        // The azimuth probe's |three columns - one| over its cells, every probe_every-th: the error.
        std::vector<double> az(size_t(K), 0.0);
        if (one && three)
            for (int b = 0; b < K; ++b)
                az[size_t(b)] =
                    images.probe_every * std::abs(linear(three->at(b, i)) - linear(one->at(b, i)));
        // Per bin, for fast's report: a bin's own sum holds the few probed cells in it, scaled (most bins
        // none, the rest probe_every times one cell's difference), which would make the |dB| quantiles
        // depend on how many cells the grid has. Each bin takes the mean over the probe_every bins centred
        // on it instead (the same total).
        std::vector<double> az_near;
        if (report) {
            std::vector<double> sum(size_t(K) + 1, 0.0);
            for (int b = 0; b < K; ++b) sum[size_t(b) + 1] = sum[size_t(b)] + az[size_t(b)];
            const int w = images.probe_every / 2;
            az_near.resize(size_t(K));
            for (int b = 0; b < K; ++b)
                az_near[size_t(b)] =
                    (sum[size_t(std::min(K, b + w + 1))] - sum[size_t(std::max(0, b - w))]) / (2 * w + 1);
        }
        for (int b = 0; b < K; ++b) {
            const float a = coarse.at(b, i), f = fine.at(b, i), m = edges ? edges->at(b, i) : a;
            const double lf = linear(f);
            const double la = a == f ? lf : linear(a), lm = m == f ? lf : m == a ? la : linear(m);
            // What the edges' merges change in full, the smooth merges' (a against m) at kSmoothShare; with
            // the lasting edges' image (u), the edges refinement will split (m against u) at kRefinableShare.
            double d = std::abs(lm - lf) + kSmoothShare * std::abs(la - lm);
            if (images.lasting_edges) {
                const float u = images.lasting_edges->at(b, i);
                const double lu = u == f ? lf : linear(u);
                d = std::abs(lu - lf) + kRefinableShare * std::abs(lm - lu) +
                    kSmoothShare * std::abs(la - lm);
            }
            e.num += d, e.den += lf;
            (acts ? e.az_num : e.az_seen) += az[size_t(b)];
            if (!(a > -INFINITY && f > -INFINITY)) continue;
            // In dB (twice the error, as d), on the coarse level's side; without the edges' image d is
            // |coarse - fine| itself.
            auto diff_db = [&](double d_all) {
                const double lc = la >= lf ? lf + d_all : lf - d_all;
                return float(std::abs(edges && lc > 0 ? 10 * std::log10(lc / lf) : double(a) - double(f)));
            };
            const float d_db = diff_db(acts ? d + 2 * az[size_t(b)] : d);
            e.diffs_db.push_back(d_db);
            if (report) {
                const double near = az_near[size_t(b)];
                e.seen_inc_db.push_back(near > 0 ? std::max(0.0f, diff_db(d + 2 * near) - d_db) : 0.0f);
            }
        }
    });
    return out;
}

TraceResult::ErrorEstimate combine_errors(const std::vector<const SampleError*>& errors, bool seen) {
    double num = 0, den = 0, az_seen = 0;
    size_t n = 0;
    for (const SampleError* e : errors)
        num += e->share(), den += e->den, az_seen += 2 * e->az_seen, n += e->diffs_db.size();
    if (seen) num += az_seen;
    std::vector<float> diffs;
    diffs.reserve(n);
    for (const SampleError* e : errors) {
        // Fast's probe, when reported: what its azimuth share adds to each bin of a probed group.
        const bool inc = seen && e->seen_inc_db.size() == e->diffs_db.size();
        for (size_t k = 0; k < e->diffs_db.size(); ++k)
            diffs.push_back(e->diffs_db[k] + (inc ? e->seen_inc_db[k] : 0.0f));
    }
    TraceResult::ErrorEstimate est;
    est.valid = true;
    auto ratio = [&](double x) { return (den > 0 ? x / den : (x > 0 ? INFINITY : 0.0)) / 2; };
    est.rel_l1 = ratio(num);
    if (seen) est.azimuth_rel_l1 = ratio(az_seen);
    if (!diffs.empty()) {
        auto q = [&](double f) {
            const size_t k = std::min(diffs.size() - 1, size_t(f * double(diffs.size() - 1) + 0.5));
            std::nth_element(diffs.begin(), diffs.begin() + long(k), diffs.end());
            return double(diffs[k]);
        };
        est.median_abs_db = q(0.5) / 2;
        est.p95_abs_db = q(0.95) / 2;
    }
    return est;
}

PolarImage columns_of(const PolarImage& img, const std::vector<int>& beams) {
    PolarImage out;
    out.bins = img.bins, out.beams = int(beams.size());
    out.level_db.assign(size_t(out.bins) * beams.size(), -std::numeric_limits<float>::infinity());
    for (int b = 0; b < img.bins; ++b)
        for (size_t k = 0; k < beams.size(); ++k)
            if (beams[k] >= 0) out.level_db[size_t(b) * beams.size() + k] = img.at(b, beams[k]);
    return out;
}

PolarImage shade_beams(const TraceResult& hits, const SceneDesc& s, const std::vector<int>& beams) {
    TraceResult sub;
    sub.beams = int(beams.size());
    sub.cells.resize(beams.size());
    const bool ghosts = !hits.ghosts.empty();
    if (ghosts) sub.ghosts.resize(beams.size());
    for (size_t k = 0; k < beams.size(); ++k) {
        if (beams[k] < 0) continue;
        sub.cells[k] = hits.cells[size_t(beams[k])];
        if (ghosts) sub.ghosts[k] = hits.ghosts[size_t(beams[k])];
    }
    return shade_columns(sub, s, sub.beams);
}

} // namespace sonarsim::adaptive

namespace sonarsim {

TraceResult::ErrorEstimate reestimate_error(const TraceResult& hits, const SceneDesc& s,
                                            const PolarImage* image) {
    if (!hits.estimate_cells)
        throw std::invalid_argument("reestimate_error: the hits keep no estimate cells (adaptive only)");
    const AdaptiveEstimateCells& k = *hits.estimate_cells;
    if (s.sonar.beams != hits.beams || (image && image->beams != hits.beams))
        throw std::invalid_argument("reestimate_error: an image of another sonar");
    const int G = int(k.samples.size());
    const PolarImage fine =
        image ? adaptive::columns_of(*image, k.samples) : adaptive::shade_beams(hits, s, k.samples);
    const PolarImage coarse = shade_columns(k.coarse, s, G), edges = shade_columns(k.coarse_edges, s, G);
    PolarImage one, three;
    if (k.probed) one = shade_columns(k.az_one, s, G), three = shade_columns(k.az_three, s, G);
    const bool strict = hits.error_estimate.strict;
    const std::vector<adaptive::SampleError> shares = adaptive::sample_errors(
        coarse, fine, k.ref_db,
        {&edges, k.probed ? &one : nullptr, k.probed ? &three : nullptr, strict, k.probe_every});
    std::vector<const adaptive::SampleError*> errs;
    for (int g = 0; g < G; ++g)
        if (k.samples[size_t(g)] >= 0) errs.push_back(&shares[size_t(g)]);
    // As trace_adaptive reports it: fast with what its probe saw, strict without (it acted on it).
    TraceResult::ErrorEstimate est = adaptive::combine_errors(errs, !strict);
    est.passes = hits.error_estimate.passes;
    est.budget_reached = hits.error_estimate.budget_reached;
    est.strict = strict;
    if (strict) est.azimuth_rel_l1 = 0;
    return est;
}

bool kept_placement_serves(const TraceResult::ErrorEstimate& anew, const TraceResult::ErrorEstimate& traced,
                           const SamplingParams& p) {
    if (anew.meets(p)) return true;
    if (traced.meets(p)) return false; // a re-trace refines until it meets them
    return anew.rel_l1 <= traced.rel_l1 + p.tolerance_rel_l1 &&
           anew.median_abs_db <= traced.median_abs_db + p.tolerance_db;
}

} // namespace sonarsim

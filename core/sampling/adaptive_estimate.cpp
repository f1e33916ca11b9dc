// Adaptive sampling: the error estimate, per group of beams and for the whole image. Each group's sample
// beam is shaded twice, from its cells and from the same cells one level coarser; the image's estimate is
// the relative L1 and the |dB| quantiles of their difference over all samples, halved (adaptive_sampler.hpp).
#include "core/sampling/adaptive_sampler.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sonarsim::adaptive {

SceneDesc sampled_beams_scene(const SceneDesc& s, int n) {
    SceneDesc out = s;
    out.sonar.beams = n;
    out.sonar.beam_table = kUniformBeams;
    return out;
}

std::vector<SampleError> sample_errors(const PolarImage& coarse, const PolarImage& fine, double ref_db,
                                       const StrictImages& strict) {
    const int N = fine.beams, K = fine.bins;
    if (std::isnan(ref_db)) ref_db = 0; // no echo estimated yet: any fixed level does
    auto linear = [&](float v) { return v > -INFINITY ? std::exp((double(v) - ref_db) * kLn10Over10) : 0.0; };
    const PolarImage *edges = strict.coarse_edges, *one = strict.az_one, *three = strict.az_three;
    std::vector<SampleError> out(static_cast<size_t>(N));
    for (int i = 0; i < N; ++i) {
        SampleError& e = out[size_t(i)];
        for (int b = 0; b < K; ++b) {
            const float a = coarse.at(b, i), f = fine.at(b, i), m = edges ? edges->at(b, i) : a;
            const double lf = linear(f);
            const double la = a == f ? lf : linear(a), lm = m == f ? lf : m == a ? la : linear(m);
            // What the edges' merges change in full, the smooth merges' (a against m) at kSmoothShare.
            const double d = std::abs(lm - lf) + kSmoothShare * std::abs(la - lm);
            // The azimuth probe's |three columns - one| over its cells, every kProbeEvery-th: the error.
            const double az =
                one && three ? kProbeEvery * std::abs(linear(three->at(b, i)) - linear(one->at(b, i))) : 0.0;
            e.num += d, e.az_num += az, e.den += lf;
            if (!(a > -INFINITY && f > -INFINITY)) continue;
            // Both in dB (twice the error, as d), on the coarse level's side.
            const double d_all = d + 2 * az, lc = la >= lf ? lf + d_all : lf - d_all;
            const double d_db = edges && lc > 0 ? 10 * std::log10(lc / lf) : double(a) - double(f);
            e.diffs_db.push_back(float(std::abs(d_db)));
        }
    }
    return out;
}

TraceResult::ErrorEstimate combine_errors(const std::vector<const SampleError*>& errors) {
    double num = 0, den = 0;
    size_t n = 0;
    for (const SampleError* e : errors) num += e->share(), den += e->den, n += e->diffs_db.size();
    std::vector<float> diffs;
    diffs.reserve(n);
    for (const SampleError* e : errors)
        for (float d : e->diffs_db) diffs.push_back(float(e->scale) * d);
    TraceResult::ErrorEstimate est;
    est.valid = true;
    est.rel_l1 = (den > 0 ? num / den : (num > 0 ? INFINITY : 0.0)) / 2;
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

} // namespace sonarsim::adaptive

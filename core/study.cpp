#include "study.hpp"

#include "shade.hpp"
#include "trace.hpp"

#include <algorithm>
#include "timing.hpp"

#include <chrono>

namespace sonarsim {
namespace {

SceneDesc with_sampling(SceneDesc s, const Sampling& m) {
    s.sampling.scheme = m.scheme;
    s.sampling.elevation_rays = m.elevation_rays;
    s.sampling.azimuth_rays = m.azimuth_rays;
    return s;
}

PolarImage render_raw(const SceneGeometry& g, const SceneDesc& s, TraceResult* hits = nullptr) {
    TraceResult t = trace(g, s);
    PolarImage img = t.shaded ? std::move(*t.shaded) : shade(t, s);
    if (hits) *hits = std::move(t);
    return img;
}

} // namespace

std::string Sampling::label() const {
    static const char* names[] = {"uniform", "spread", "adaptive"};
    return std::string(names[int(scheme)]) + " " + std::to_string(elevation_rays) + "x" +
           std::to_string(azimuth_rays);
}

StudyReference make_reference(const SceneGeometry& g, const SceneDesc& s) {
    StudyReference ref;
    const auto t0 = std::chrono::steady_clock::now();
    if (has_floor_reference(s)) {
        ref.kind = "semi-analytic floor integral";
        ref.description =
            "Gauss-Legendre, 32 azimuth panels x 8 nodes per beam, elevation split at bin-edge roots";
        ref.image = floor_reference(s, 32);
        ref.time_ms = ms_since(t0);
        ref.convergence = compare_images(floor_reference(s, 8), ref.image);
        return ref;
    }
    // Far denser than any ladder setting; its convergence is shown against a 3x coarser run.
    SceneDesc dense = with_sampling(s, {SamplingScheme::Adaptive, 6561, 9});
    dense.sampling.tolerance_db = 1e-3;
    ref.kind = "dense adaptive run";
    ref.description = "adaptive, base 6561 x 9 rays per beam, tolerance 0.001 dB";
    ref.image = render_raw(g, dense);
    ref.time_ms = ms_since(t0);
    SceneDesc coarser = with_sampling(dense, {SamplingScheme::Adaptive, 2187, 3});
    ref.convergence = compare_images(render_raw(g, coarser), ref.image);
    return ref;
}

StudyRow measure(const SceneGeometry& g, const SceneDesc& scene, const Sampling& m, int repeats,
                 const PolarImage& reference) {
    const SceneDesc s = with_sampling(scene, m);
    StudyRow row;
    row.sampling = m;
    std::vector<double> times;
    PolarImage img;
    TraceResult hits;
    for (int r = 0; r < std::max(1, repeats); ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        img = render_raw(g, s, &hits);
        times.push_back(ms_since(t0));
    }
    std::sort(times.begin(), times.end());
    row.time_ms = times[times.size() / 2];
    row.rays = double(hits.rays_traced);
    row.estimate = hits.error_estimate;
    row.error = compare_images(img, reference);
    return row;
}

std::vector<Sampling> default_ladder(bool quick) {
    using S = SamplingScheme;
    std::vector<Sampling> v = {{S::Uniform, 281, 1},   {S::Uniform, 1000, 1}, {S::Uniform, 3000, 2},
                               {S::Uniform, 10000, 4}, {S::Spread, 31, 1},    {S::Spread, 101, 1},
                               {S::Spread, 281, 1},    {S::Spread, 1000, 2},  {S::Spread, 3000, 4},
                               {S::Adaptive, 11, 1},   {S::Adaptive, 31, 1},  {S::Adaptive, 101, 1},
                               {S::Adaptive, 281, 1},  {S::Adaptive, 1000, 2}};
    if (quick)
        v.erase(std::remove_if(
                    v.begin(), v.end(),
                    [](const Sampling& m) { return double(m.elevation_rays) * m.azimuth_rays > 3000; }),
                v.end());
    return v;
}

} // namespace sonarsim

#include "core/sensor/sensor.hpp"

#include "core/base/fast_math.hpp"
#include "core/data/pose.hpp"
#include "core/base/scratch_pool.hpp"
#include "core/scene/params.hpp"
#include "core/grid/sonar_grid.hpp"
#include "core/grid/sensor_patterns.hpp"
#include "core/sensor/row_effects.hpp"
#include "core/sensor/speckle_field.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace sonarsim {
namespace {

/// 10^((level - peak) / 10) of each level.
SONARSIM_SIMD_CLONES void linear_of(std::size_t n, const float* level_db, double peak_db, double* out) {
    constexpr double kLog2Of10Over10 = 0.33219280948873623;
    for (std::size_t i = 0; i < n; ++i)
        out[i] = fast::exp2_nonpositive((double(level_db[i]) - peak_db) * kLog2Of10Over10);
}

/// The output levels of a row: 10 log10(v) + gain [dB], -inf where v is 0.
SONARSIM_SIMD_CLONES void levels_db(int n, const double* v, double gain_db, float* out) {
    for (int i = 0; i < n; ++i) {
        const float level = float(fast::db_level(v[i]) + gain_db);
        out[i] = v[i] > 0 ? level : -std::numeric_limits<float>::infinity();
    }
}

/// The image's largest level [dB] (0 when nothing echoes), in chunks in parallel.
double peak_level(const PolarImage& src) {
    const std::size_t n = src.level_db.size(), chunk = std::size_t(1) << 16, chunks = (n + chunk - 1) / chunk;
    std::vector<float> top(chunks);
    tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t c) {
        top[c] = max_level(std::min(chunk, n - c * chunk), src.level_db.data() + c * chunk);
    });
    const float peak = max_level(chunks, top.data());
    return peak == -std::numeric_limits<float>::infinity() ? 0.0 : double(peak);
}

/// Linear intensity relative to 10^(peak/10) (0 where -inf).
void to_linear(const PolarImage& src, double peak_db, std::vector<double>& out) {
    out = scratch::take<double>(src.level_db.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, out.size(), 1 << 14), [&](auto r) {
        linear_of(r.size(), src.level_db.data() + r.begin(), peak_db, out.data() + r.begin());
    });
}

/// The receive pattern: each beam sums the fine columns weighted by its pattern (peak gain 1).
std::vector<double> form_beams(const std::vector<double>& in, int K, int J, const SceneDesc& s) {
    const std::shared_ptr<const AzimuthBeamforming> shared = shared_azimuth_beamforming(s, false);
    const AzimuthBeamforming& bf = *shared;
    const int N = bf.beams;
    std::vector<double> out(size_t(K) * N, 0.0);
    tbb::parallel_for(0, K, [&](int k) {
        const double* x = in.data() + size_t(k) * J;
        double* row = out.data() + size_t(k) * N;
        for (int j = 0; j < J; ++j) {
            const double v = x[j];
            if (v == 0) continue;
            const double* w = bf.weight.data() + bf.offset[size_t(j)];
            double* o = row + bf.first[size_t(j)];
            for (int t = 0, n = bf.count[size_t(j)]; t < n; ++t) o[t] += w[t] * v;
        }
    });
    return out;
}

} // namespace

double tvg_db(Tvg law, double r, double alpha) {
    const int n = law == Tvg::Log20 ? 20 : law == Tvg::Log30 ? 30 : law == Tvg::Log40 ? 40 : 0;
    return n == 0 ? 0.0 : n * std::log10(r) + 2 * alpha * r;
}

bool sensor_is_ideal(const SceneDesc& s) {
    // The effect switches are the table's rows with an ideal value (ParamSpec::ideal_value); the elevation
    // pattern, the one acting in the trace, is in the ideal image already.
    for (const ParamSpec& p : scene_params())
        if (!p.ideal_value.is_null() && p.stage != Stage::Trace && p.get(s) != p.ideal_value) return false;
    return true;
}

PolarImage apply_sensor(const PolarImage& ideal, const SensorInputs* inputs, const SceneDesc& s,
                        double alpha) {
    const int K = ideal.bins, N = ideal.beams;
    const size_t cells = size_t(K) * size_t(N);
    const std::shared_ptr<const SonarGrid> sg = sonar_grid(s.sonar);
    const double r_min = sg->range_min_m, dr = sg->bin_m;
    const SensorParams& p = s.sensor;

    // 1-4. Linear intensity relative to the peak. With speckle, a complex field anchored to the scatterers
    // formed through the receive pattern and the matched filter (speckle_field.hpp); otherwise the
    // intensities formed into beams by the receive pattern, then the matched filter along range.
    const bool fine = inputs && inputs->sub > 1 && p.azimuth_window != AzimuthWindow::None;
    const PolarImage& src = fine ? inputs->fine : ideal;
    std::vector<double> I;
    const bool speckle = p.speckle != Speckle::Off && inputs && !inputs->elevation_rad.empty();
    // With speckle, the image's peak from the blocks' that the field is carried relative to (one pass).
    const std::vector<float> block_peaks = speckle ? speckle_block_peaks(src) : std::vector<float>{};
    const float block_peak = max_level(block_peaks.size(), block_peaks.data());
    const double peak = !speckle                                                ? peak_level(src)
                        : block_peak == -std::numeric_limits<float>::infinity() ? 0.0
                                                                                : double(block_peak);
    if (speckle) {
        I = form_speckle(src, peak, *inputs, s, &block_peaks);
    } else {
        to_linear(src, peak, I);
        if (p.azimuth_window != AzimuthWindow::None) {
            std::vector<double> beams = form_beams(I, K, src.beams, s);
            scratch::give(std::move(I));
            I = std::move(beams);
        }
        if (const std::vector<double> h = range_kernel(p.pulse, p.range_resolution_m, dr); h.size() > 1)
            convolve_range(I, K, N, h);
    }

    // 4-6. The row effects in their order (row_effects.hpp: a beam table's response, the K texture, noise),
    // then TVG and gain.
    const RowContext context{s, *sg, inputs, peak, speckle};
    std::vector<std::unique_ptr<const RowEffect>> effects;
    for (const RowEffectEntry& e : row_effects())
        if (auto effect = e.make(context)) effects.push_back(std::move(effect));
    PolarImage out;
    out.bins = K, out.beams = N;
    out.level_db = scratch::take<float>(cells); // every value written below
    tbb::parallel_for(0, K, [&](int k) {
        const double r = r_min + (k + 0.5) * dr;
        double* v = I.data() + size_t(k) * N; // this row's, worked on in place
        for (const auto& effect : effects) effect->apply(k, r, v);
        levels_db(N, v, tvg_db(p.tvg, r, alpha) + p.gain_db + peak, out.level_db.data() + size_t(k) * N);
    });
    scratch::give(std::move(I));
    return out;
}

} // namespace sonarsim

#include "core/sensor/sensor.hpp"

#include "core/base/fast_math.hpp"
#include "core/data/pose.hpp"
#include "core/base/scratch_pool.hpp"
#include "core/scene/params.hpp"
#include "core/grid/sonar_grid.hpp"
#include "core/sensor/keyed_variates.hpp"
#include "core/grid/sensor_patterns.hpp"
#include "core/sensor/speckle_field.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace sonarsim {
namespace {

std::uint64_t bits_of(double x) {
    std::uint64_t u;
    std::memcpy(&u, &x, sizeof u);
    return u;
}

/// A key for everything that decides where the sonar looks from (and which ping it is): noise stays put
/// while nothing moves.
std::uint64_t pose_key(const SceneDesc& s) {
    std::uint64_t h = mix64(std::uint64_t(s.sensor.seed) ^ 0x6e6f697365ULL); // "noise"
    for (double v : s.sonar.pose.position_m) h = mix64(h ^ bits_of(v));
    for (double v : s.sonar.pose.orientation_deg) h = mix64(h ^ bits_of(v));
    if (s.sensor.noise_draw) h = mix64(h ^ s.sensor.noise_draw); // a ping's own draw (an image has none)
    return h;
}

/// 10^((level - peak) / 10) of each level.
SONARSIM_SIMD_CLONES void linear_of(std::size_t n, const float* level_db, double peak_db, double* out) {
    constexpr double kLog2Of10Over10 = 0.33219280948873623;
    for (std::size_t i = 0; i < n; ++i)
        out[i] = fast::exp2_nonpositive((double(level_db[i]) - peak_db) * kLog2Of10Over10);
}

/// |sqrt(v) + n|^2 for a row of intensities v, n = sigma sqrt(E) e^(i phi) circular complex Gaussian of power
/// sigma^2 keyed by the row's key and the beam (key, power, cos_phase, sin_phase: scratch of n values).
SONARSIM_SIMD_CLONES void add_noise(int n, std::uint32_t row_key, double noise_power, std::uint32_t* key,
                                    float* power, float* cos_phase, float* sin_phase, double* v) {
    for (int b = 0; b < n; ++b) key[b] = keyed::mix32(row_key + std::uint32_t(b));
    keyed::exp_phasors(n, key, power, cos_phase, sin_phase); // the sine unused
    const double sigma = std::sqrt(noise_power);
    for (int b = 0; b < n; ++b) {
        const double E = power[b];
        v[b] = v[b] + noise_power * E + 2 * sigma * std::sqrt(v[b] * E) * double(cos_phase[b]);
    }
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

    // 4-6. The K texture per resolution cell, noise anchored to the pose, then TVG and gain.
    const bool k_dist = speckle && p.speckle == Speckle::K;
    const double noise_power = p.noise ? std::pow(10.0, -peak / 10) : 0.0; // L_EN of noise is 0 dB
    const SonarFrame frame(s);
    const double spacing = sg->spacing_rad;
    std::vector<double> ahead_x(static_cast<size_t>(N)), ahead_y(ahead_x), ahead_z(ahead_x);
    for (int b = 0; b < N; ++b) {
        const glm::dvec3 a = frame.ahead(sg->beam_azimuth_rad(b));
        ahead_x[size_t(b)] = a.x, ahead_y[size_t(b)] = a.y, ahead_z[size_t(b)] = a.z;
    }
    std::vector<double> beam_gain; // a table's relative response per beam (none: every beam 1)
    if (sg->table())
        for (int b = 0; b < N; ++b) beam_gain.push_back(sg->beam_gain(b));
    const std::uint64_t texture_seed = mix64(std::uint64_t(p.seed) ^ 0x737065636b6c65ULL); // "speckle"
    const std::uint64_t noise_seed = pose_key(s);
    PolarImage out;
    out.bins = K, out.beams = N;
    out.level_db = scratch::take<float>(cells); // every value written below
    tbb::parallel_for(0, K, [&](int k) {
        struct Scratch {
            std::vector<double> rise, reach, texture;
            std::vector<std::uint32_t> key;
            std::vector<float> power, cos_phase, sin_phase;
        };
        thread_local Scratch w; // a leaf task's: nothing else runs on this thread while it is in use
        const double r = r_min + (k + 0.5) * dr;
        const double gain = tvg_db(p.tvg, r, alpha) + p.gain_db + peak;
        const size_t c0 = size_t(k) * N;
        double* v = I.data() + c0; // this row's, worked on in place
        if (!beam_gain.empty())
            for (int b = 0; b < N; ++b) v[b] *= beam_gain[size_t(b)];
        w.key.resize(size_t(N));
        if (k_dist && std::any_of(v, v + N, [](double x) { return x > 0; })) {
            // The texture's cells: world points on a grid of half a range bin (or half the beam spacing
            // across).
            for (auto* a : {&w.rise, &w.reach, &w.texture}) a->resize(size_t(N));
            frame.raise(r, N, 1, inputs->elevation_rad.data() + c0, w.rise.data(), w.reach.data());
            WorldKeyGrid(texture_seed, std::min(dr, r * spacing))
                .keys(N,
                      frame.points(w.rise.data(), w.reach.data(), ahead_x.data(), ahead_y.data(),
                                   ahead_z.data()),
                      w.key.data());
            keyed::gamma_unit_mean(N, w.key.data(), p.speckle_k_shape, w.texture.data());
            for (int b = 0; b < N; ++b) v[b] *= w.texture[size_t(b)];
        }
        if (noise_power > 0) {
            const std::uint32_t row_key = keyed::fold(mix64(noise_seed ^ std::uint64_t(k)));
            for (auto* a : {&w.power, &w.cos_phase, &w.sin_phase}) a->resize(size_t(N));
            add_noise(N, row_key, noise_power, w.key.data(), w.power.data(), w.cos_phase.data(),
                      w.sin_phase.data(), v);
        }
        levels_db(N, v, gain, out.level_db.data() + c0);
    });
    scratch::give(std::move(I));
    return out;
}

} // namespace sonarsim

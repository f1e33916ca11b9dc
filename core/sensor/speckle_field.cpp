#include "core/sensor/speckle_field.hpp"

#include "core/base/fast_math.hpp"
#include "core/base/scratch_pool.hpp"
#include "core/grid/sonar_grid.hpp"
#include "core/sensor/sensor.hpp"
#include "core/grid/sensor_patterns.hpp"
#include "core/sensor/speckle_beams.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace sonarsim {
namespace {

/// Range bins whose field is carried relative to one amplitude: the strongest sample of the block's bins.
constexpr int kBlockRows = 8;
/// Blocks formed together, kSpeckleGroupRows bins (speckle_beams.hpp).
constexpr int kGroupBlocks = 2, kGroupRows = kSpeckleGroupRows;
static_assert(kGroupBlocks * kBlockRows == kGroupRows, "a group is whole blocks");

/// The largest of n levels [dB] (-inf when there is none; NaN is passed over). On the bits, where
/// i ^ ((i >> 31) & 0x7fffffff) orders as the floats do and an integer maximum vectorises.
SONARSIM_SIMD_CLONES float max_level_clones(std::size_t n, const float* level_db) {
    auto order = [](std::int32_t i) { return i ^ ((i >> 31) & 0x7fffffff); }; // its own inverse
    const std::int32_t lowest = order(fast::bits_of(-std::numeric_limits<float>::infinity()));
    std::int32_t top = lowest;
    for (std::size_t i = 0; i < n; ++i) {
        const float v = level_db[i];
        top = std::max(top, v == v ? order(fast::bits_of(v)) : lowest);
    }
    return fast::float_of(order(top));
}

} // namespace

float max_level(std::size_t n, const float* level_db) {
    return max_level_clones(n, level_db);
}

namespace {

/// The field of one row relative to the amplitude 10^(top_db / 20), in single precision: 0 for levels more
/// than 759 dB below top_db (2^-126 in amplitude).
SONARSIM_SIMD_CLONES void relative_field_row(int J, const float* level_db, float top_db, const float* power,
                                             const float* cos_phase, const float* sin_phase, float* re,
                                             float* im) {
    constexpr float kLog2Of10Over20 = 0.166096405f;
    for (int j = 0; j < J; ++j) {
        const float a =
            fast::exp2_nonpositive_f((level_db[j] - top_db) * kLog2Of10Over20) * std::sqrt(power[j]);
        re[j] = a * cos_phase[j], im[j] = a * sin_phase[j];
    }
}

/// 4 beams of one row in double precision (an AVX register, two SSE ones) and the same in single.
typedef double FourDoubles __attribute__((vector_size(4 * sizeof(double))));
typedef float FourFloats __attribute__((vector_size(4 * sizeof(float))));

/// One output row: |sum_t g[t + half] unit(k - t) A_(k - t)|^2 over the rows of A (re N values, then im N
/// values; row k relative to the amplitude unit[k / kBlockRows]), 4 beams at a time summed over the taps.
SONARSIM_SIMD_CLONES void intensity_row(const float* A, const double* unit, int K, int N, int k,
                                        const std::vector<double>& g, double* out) {
    thread_local std::vector<double> w; // the taps within the image: weights and rows (only within this call)
    thread_local std::vector<const float*> x;
    w.clear(), x.clear();
    const int half = int(g.size() / 2);
    for (int t = -half; t <= half; ++t) {
        const int src = k - t;
        if (src < 0 || src >= K) continue;
        w.push_back(g[size_t(t + half)] * unit[src / kBlockRows]), x.push_back(A + size_t(src) * 2 * N);
    }
    const int taps = int(w.size());
    int b = 0;
    for (; b + 4 <= N; b += 4) {
        FourDoubles re = {}, im = {};
        for (int q = 0; q < taps; ++q) {
            FourFloats x_re, x_im;
            std::memcpy(&x_re, x[size_t(q)] + b, sizeof x_re);
            std::memcpy(&x_im, x[size_t(q)] + N + b, sizeof x_im);
            re += w[size_t(q)] * __builtin_convertvector(x_re, FourDoubles);
            im += w[size_t(q)] * __builtin_convertvector(x_im, FourDoubles);
        }
        const FourDoubles intensity = re * re + im * im;
        std::memcpy(out + b, &intensity, sizeof intensity);
    }
    for (; b < N; ++b) {
        double re = 0, im = 0;
        for (int q = 0; q < taps; ++q)
            re += w[size_t(q)] * double(x[size_t(q)][b]), im += w[size_t(q)] * double(x[size_t(q)][N + b]);
        out[b] = re * re + im * im;
    }
}

/// Per beam, the rise r sin(e) along `up` and the reach r cos(e) along `ahead` (e NaN: 0).
SONARSIM_SIMD_CLONES void rise_and_reach(int n, double r_m, const float* elevation_rad, double* rise_m,
                                         double* reach_m) {
    for (int b = 0; b < n; ++b) {
        const double e = elevation_rad[b] == elevation_rad[b] ? elevation_rad[b] : 0.0; // NaN: nothing echoes
        rise_m[b] = r_m * SonarFrame::key_sin(e), reach_m[b] = r_m * SonarFrame::key_cos(e);
    }
}

/// Each of n values `per_beam` times in a row.
SONARSIM_SIMD_CLONES void spread(int n, int per_beam, const double* in, double* out) {
    if (per_beam == 2) { // the common case, in a loop that vectorises
        for (int b = 0; b < n; ++b) out[2 * b] = out[2 * b + 1] = in[b];
        return;
    }
    for (int b = 0, j = 0; b < n; ++b)
        for (int s = 0; s < per_beam; ++s, ++j) out[j] = in[b];
}

} // namespace

void SonarFrame::raise(double r_m, int cells, int per_beam, const float* elevation_rad, double* rise,
                       double* reach) const {
    if (per_beam == 1) return rise_and_reach(cells, r_m, elevation_rad, rise, reach);
    thread_local std::vector<double> beam_rise, beam_reach; // used only within this call
    const int beams = cells / per_beam;
    beam_rise.resize(size_t(beams)), beam_reach.resize(size_t(beams));
    rise_and_reach(beams, r_m, elevation_rad, beam_rise.data(), beam_reach.data());
    spread(beams, per_beam, beam_rise.data(), rise), spread(beams, per_beam, beam_reach.data(), reach);
}

WorldKeyGrid::WorldKeyGrid(std::uint64_t seed, double cell_m) {
    const int q_exp = int(std::floor(std::log2(0.5 * cell_m)));
    inv_q_per_m_ = std::ldexp(1.0, -q_exp);
    row_seed_ = keyed::fold(mix64(seed ^ std::uint64_t(std::int64_t(q_exp))));
}

SonarFrame::SonarFrame(const SceneDesc& s)
    : origin(to_glm(s.sonar.pose.position_m)), R(rotation_matrix(s.sonar.pose.orientation_deg)) {
    up = R * glm::dvec3(0, 0, 1);
}

glm::dvec3 SonarFrame::ahead(double a) const {
    return R * glm::dvec3(std::cos(a), std::sin(a), 0);
}

void convolve_range(std::vector<double>& rows, int K, int width, const std::vector<double>& h) {
    const int half = int(h.size() / 2);
    std::vector<double> out(rows.size(), 0.0);
    tbb::parallel_for(0, K, [&](int k) {
        double* o = out.data() + size_t(k) * width;
        for (int t = -half; t <= half; ++t) {
            const int src = k - t;
            if (src < 0 || src >= K) continue;
            const double w = h[size_t(t + half)];
            const double* x = rows.data() + size_t(src) * width;
            for (int b = 0; b < width; ++b) o[b] += w * x[b];
        }
    });
    rows.swap(out);
}

std::vector<float> speckle_block_peaks(const PolarImage& src) {
    const int K = src.bins, J = src.beams, blocks = (K + kBlockRows - 1) / kBlockRows;
    std::vector<float> top(static_cast<size_t>(blocks));
    tbb::parallel_for(0, blocks, [&](int block) {
        const int k0 = block * kBlockRows, rows = std::min(kBlockRows, K - k0);
        top[size_t(block)] = max_level(size_t(rows) * J, src.level_db.data() + size_t(k0) * J);
    });
    return top;
}

std::vector<double> form_speckle(const PolarImage& src, double peak_db, const SensorInputs& in,
                                 const SceneDesc& s, const std::vector<float>* block_peaks) {
    const int K = src.bins, J = src.beams;
    const std::shared_ptr<const SonarGrid> sg = sonar_grid(s.sonar);
    const int N = sg->beams, S = J / N;
    const double r_min = sg->range_min_m, dr = sg->bin_m;
    const double column = sg->fov_rad / J; // the mean column's width [rad]
    const SonarFrame frame(s);
    std::vector<double> ahead_x(static_cast<size_t>(J)), ahead_y(ahead_x), ahead_z(ahead_x);
    for (int j = 0; j < J; ++j) {
        const glm::dvec3 a = frame.ahead(sg->column_azimuth_rad(j, S));
        ahead_x[size_t(j)] = a.x, ahead_y[size_t(j)] = a.y, ahead_z[size_t(j)] = a.z;
    }
    const bool formed = s.sensor.azimuth_window != AzimuthWindow::None;
    const std::shared_ptr<const BeamSums> shared_sums = formed ? shared_beam_sums(s) : nullptr;
    const std::uint64_t seed = mix64(std::uint64_t(s.sensor.seed) ^ 0x677261696eULL); // "grain"

    // Per group of blocks of range bins: the field on the source columns, then (formed) the beams' complex
    // amplitudes into A (per bin, re of the N beams, then im), or, formed with a single-tap range filter,
    // straight their intensities.
    const int blocks = (K + kBlockRows - 1) / kBlockRows, groups = (blocks + kGroupBlocks - 1) / kGroupBlocks;
    const std::vector<double> g =
        range_amplitude_kernel(s.sensor.pulse, s.sensor.range_resolution_m, dr); // the matched filter
    const bool single_tap = g.size() == 1;
    // Formed with a single-tap filter: each beam's |.|^2 straight from its sums (no A).
    const bool fused = formed && single_tap;
    std::vector<float> A =
        fused ? std::vector<float>{} : scratch::take<float>(size_t(K) * N * 2); // every value written below
    std::vector<double> out = scratch::take<double>(size_t(K) * N);             // every value written below
    std::vector<double> unit(static_cast<size_t>(blocks)); // per block: A's unit amplitude
    tbb::parallel_for(0, groups, [&](int group) {
        struct Scratch {
            std::vector<double> rise, reach;
            std::vector<std::uint32_t> key;
            std::vector<float> power, cos_phase, sin_phase, rows, group;
        };
        thread_local Scratch w; // a leaf task's: nothing else runs on this thread while it is in use
        w.rise.resize(size_t(J)), w.reach.resize(size_t(J));
        for (auto* v : {&w.power, &w.cos_phase, &w.sin_phase}) v->resize(size_t(J));
        w.rows.resize(formed ? size_t(J) * 2 * kGroupRows : 0);
        w.key.resize(size_t(J));
        w.group.resize(formed ? size_t(J) * 2 * kGroupRows + 16 : 0); // 16: room to align
        float* const field =
            formed ? w.group.data() + (16 - (reinterpret_cast<std::uintptr_t>(w.group.data()) / 4) % 16) % 16
                   : nullptr;
        const int g0 = group * kGroupRows, group_rows = std::min(kGroupRows, K - g0);
        bool echoes = false; // whether any block of the group has a field
        for (int block = group * kGroupBlocks; block < std::min(blocks, (group + 1) * kGroupBlocks);
             ++block) {
            const int k0 = block * kBlockRows, rows = std::min(kBlockRows, K - k0);
            // In single precision relative to the block's strongest sample.
            const float top_db = block_peaks
                                     ? (*block_peaks)[size_t(block)]
                                     : max_level(size_t(rows) * J, src.level_db.data() + size_t(k0) * J);
            constexpr double kLog2Of10Over20 = 0.16609640474436812;
            unit[size_t(block)] = top_db == -std::numeric_limits<float>::infinity()
                                      ? 0.0
                                      : fast::exp2_nonpositive((double(top_db) - peak_db) * kLog2Of10Over20);
            if (unit[size_t(block)] == 0) { // nothing echoes in these bins: no field to draw
                if (fused)
                    std::fill(out.begin() + std::ptrdiff_t(size_t(k0) * N),
                              out.begin() + std::ptrdiff_t(size_t(k0 + rows) * N), 0.0);
                else
                    std::fill(A.begin() + std::ptrdiff_t(size_t(k0) * N * 2),
                              A.begin() + std::ptrdiff_t(size_t(k0 + rows) * N * 2), 0.0f);
                if (formed) // its rows form zeros (+0, as filled)
                    std::fill(w.rows.begin() + std::ptrdiff_t(size_t(k0 - g0) * 2 * J),
                              w.rows.begin() + std::ptrdiff_t(size_t(k0 - g0 + rows) * 2 * J), 0.0f);
                continue;
            }
            echoes = true;
            for (int t = 0; t < rows; ++t) {
                const int k = k0 + t;
                const double r = r_min + (k + 0.5) * dr;
                frame.raise(r, J, S, in.elevation_rad.data() + size_t(k) * N, w.rise.data(), w.reach.data());
                WorldKeyGrid(seed, std::min(dr, r * column))
                    .keys(J,
                          frame.points(w.rise.data(), w.reach.data(), ahead_x.data(), ahead_y.data(),
                                       ahead_z.data()),
                          w.key.data());
                keyed::exp_phasors(J, w.key.data(), w.power.data(), w.cos_phase.data(), w.sin_phase.data());
                const float* level = src.level_db.data() + size_t(k) * J;
                if (!formed) {
                    float* row = A.data() + size_t(k) * N * 2;
                    relative_field_row(J, level, top_db, w.power.data(), w.cos_phase.data(),
                                       w.sin_phase.data(), row, row + N);
                    continue;
                }
                float* row = w.rows.data() + size_t(k - g0) * 2 * J;
                relative_field_row(J, level, top_db, w.power.data(), w.cos_phase.data(), w.sin_phase.data(),
                                   row, row + J);
            }
        }
        if (formed && echoes) {
            std::fill(w.rows.begin() + std::ptrdiff_t(size_t(group_rows) * 2 * J), w.rows.end(),
                      0.0f); // rows past the image: zeros
            to_columns(J, w.rows.data(), field);
            double scale[kGroupRows] = {}; // the filter's weight times each row's unit
            for (int t = 0; t < group_rows; ++t) scale[t] = g[0] * unit[size_t(g0 + t) / kBlockRows];
            form_group(*shared_sums, N, field, group_rows, A.data() + size_t(g0) * N * 2, scale,
                       fused ? out.data() + size_t(g0) * N : nullptr);
        }
        if (single_tap && !fused)
            for (int k = g0; k < g0 + group_rows; ++k)
                intensity_row(A.data(), unit.data(), K, N, k, g, out.data() + size_t(k) * N);
    });

    // The matched filter along range on the amplitudes, then |.|^2 (in the group's task already when the
    // filter is a single tap: A's rows are still in cache there).
    if (!single_tap)
        tbb::parallel_for(tbb::blocked_range<int>(0, K, 16), [&](const tbb::blocked_range<int>& ks) {
            for (int k = ks.begin(); k < ks.end(); ++k)
                intensity_row(A.data(), unit.data(), K, N, k, g, out.data() + size_t(k) * N);
        });
    if (!fused) scratch::give(std::move(A));
    return out;
}

} // namespace sonarsim

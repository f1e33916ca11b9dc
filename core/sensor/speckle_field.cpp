#include "core/sensor/speckle_field.hpp"

#include "core/base/fast_math.hpp"
#include "core/base/scratch_pool.hpp"
#include "core/scene/sonar_grid.hpp"
#include "core/sensor/sensor.hpp"
#include "core/sensor/sensor_patterns.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace sonarsim {
namespace {

/// Range bins formed together: the field of a block is stored column by column, kBlockRows values (one per
/// bin) a column, so that forming a beam is a sum of whole columns, kBlockRows lanes wide.
constexpr int kBlockRows = 8;

/// The receive pattern's amplitude by beam: beam b sums the fine columns column[start[b] ... start[b + 1])
/// with the weights beside them (ascending columns), in single precision like the field it forms.
struct BeamSums {
    std::vector<int> start, column;
    std::vector<float> weight;
};

BeamSums by_beam(const AzimuthBeamforming& bf, int J) {
    BeamSums s;
    s.start.assign(size_t(bf.beams) + 1, 0);
    for (int j = 0; j < J; ++j)
        for (int t = 0; t < bf.count[size_t(j)]; ++t) ++s.start[size_t(bf.first[size_t(j)] + t) + 1];
    for (int b = 0; b < bf.beams; ++b) s.start[size_t(b) + 1] += s.start[size_t(b)];
    s.column.resize(size_t(s.start.back())), s.weight.resize(size_t(s.start.back()));
    std::vector<int> next(s.start.begin(), s.start.end() - 1);
    for (int j = 0; j < J; ++j)
        for (int t = 0; t < bf.count[size_t(j)]; ++t) {
            const int p = next[size_t(bf.first[size_t(j)] + t)]++;
            s.column[size_t(p)] = j,
            s.weight[size_t(p)] = float(bf.amplitude[bf.offset[size_t(j)] + size_t(t)]);
        }
    return s;
}

/// The largest of n levels [dB] (-inf when there is none; NaN is passed over). On the bits, where
/// i ^ ((i >> 31) & 0x7fffffff) orders as the floats do and an integer maximum vectorises.
SONARSIM_AVX2_CLONES float max_level_clones(std::size_t n, const float* level_db) {
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
SONARSIM_AVX2_CLONES void relative_field_row(int J, const float* level_db, float top_db, const float* power,
                                             const float* cos_phase, const float* sin_phase, float* re,
                                             float* im) {
    constexpr float kLog2Of10Over20 = 0.166096405f;
    for (int j = 0; j < J; ++j) {
        const float a =
            fast::exp2_nonpositive_f((level_db[j] - top_db) * kLog2Of10Over20) * std::sqrt(power[j]);
        re[j] = a * cos_phase[j], im[j] = a * sin_phase[j];
    }
}

/// The beams of a block from its field (re, im of column j, row t at j * kBlockRows + t): (re, im) of beam b
/// for the block's row t into out[t * 2 N + b] and out[t * 2 N + N + b], t < rows. The block's rows in
/// vectors of W floats (GCC's vector extension): W = 8 fills an AVX register, W = 4 an SSE one.
template <int W>
inline __attribute__((always_inline)) void form_block_lanes(const BeamSums& sums, int N, const float* re,
                                                            const float* im, int rows, float* out) {
    typedef float Lanes __attribute__((vector_size(W * sizeof(float))));
    constexpr int kParts = kBlockRows / W;
    for (int b = 0; b < N; ++b) {
        Lanes sum_re[kParts] = {}, sum_im[kParts] = {};
        for (int p = sums.start[size_t(b)]; p < sums.start[size_t(b) + 1]; ++p) {
            const float w = sums.weight[size_t(p)];
            const float* x_re = re + size_t(sums.column[size_t(p)]) * kBlockRows;
            const float* x_im = im + size_t(sums.column[size_t(p)]) * kBlockRows;
            for (int h = 0; h < kParts; ++h) {
                Lanes a, c;
                std::memcpy(&a, x_re + h * W, sizeof a);
                std::memcpy(&c, x_im + h * W, sizeof c);
                sum_re[h] += w * a, sum_im[h] += w * c;
            }
        }
        float beam_re[kBlockRows], beam_im[kBlockRows]; // the sums out of their registers
        std::memcpy(beam_re, sum_re, sizeof beam_re), std::memcpy(beam_im, sum_im, sizeof beam_im);
        for (int t = 0; t < rows; ++t)
            out[size_t(t) * 2 * N + size_t(b)] = beam_re[t],
                                    out[size_t(t) * 2 * N + size_t(N + b)] = beam_im[t];
    }
}

#ifdef SONARSIM_AVX2_DISPATCH
__attribute__((target("avx2"))) void form_block_avx2(const BeamSums& sums, int N, const float* re,
                                                     const float* im, int rows, float* out) {
    form_block_lanes<8>(sums, N, re, im, rows, out);
}
#endif

/// form_block_lanes with the widest vectors the CPU has (the same sums either way).
void form_block(const BeamSums& sums, int N, const float* re, const float* im, int rows, float* out) {
#ifdef SONARSIM_AVX2_DISPATCH
    static const bool avx2 = __builtin_cpu_supports("avx2");
    if (avx2) return form_block_avx2(sums, N, re, im, rows, out);
#endif
    form_block_lanes<4>(sums, N, re, im, rows, out);
}

/// 4 beams of one row in double precision (an AVX register, two SSE ones) and the same in single.
typedef double FourDoubles __attribute__((vector_size(4 * sizeof(double))));
typedef float FourFloats __attribute__((vector_size(4 * sizeof(float))));

/// One output row: |sum_t g[t + half] unit(k - t) A_(k - t)|^2 over the rows of A (re N values, then im N
/// values; row k relative to the amplitude unit[k / kBlockRows]), 4 beams at a time summed over the taps.
SONARSIM_AVX2_CLONES void intensity_row(const float* A, const double* unit, int K, int N, int k,
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
SONARSIM_AVX2_CLONES void rise_and_reach(int n, double r_m, const float* elevation_rad, double* rise_m,
                                         double* reach_m) {
    for (int b = 0; b < n; ++b) {
        const double e = elevation_rad[b] == elevation_rad[b] ? elevation_rad[b] : 0.0; // NaN: nothing echoes
        rise_m[b] = r_m * SonarFrame::key_sin(e), reach_m[b] = r_m * SonarFrame::key_cos(e);
    }
}

} // namespace

void SonarFrame::raise(double r_m, int cells, int per_beam, const float* elevation_rad, double* rise,
                       double* reach) const {
    if (per_beam == 1) return rise_and_reach(cells, r_m, elevation_rad, rise, reach);
    thread_local std::vector<double> beam_rise, beam_reach; // used only within this call
    const int beams = cells / per_beam;
    beam_rise.resize(size_t(beams)), beam_reach.resize(size_t(beams));
    rise_and_reach(beams, r_m, elevation_rad, beam_rise.data(), beam_reach.data());
    for (int b = 0, j = 0; b < beams; ++b) {
        const double beam_rise_m = beam_rise[size_t(b)], beam_reach_m = beam_reach[size_t(b)];
        for (int s = 0; s < per_beam; ++s, ++j) rise[j] = beam_rise_m, reach[j] = beam_reach_m;
    }
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

std::vector<double> form_speckle(const PolarImage& src, double peak_db, const SensorInputs& in,
                                 const SceneDesc& s) {
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
    const BeamSums sums = formed ? by_beam(make_azimuth_beamforming(s, true), J) : BeamSums{};
    const std::uint64_t seed = mix64(std::uint64_t(s.sensor.seed) ^ 0x677261696eULL); // "grain"

    // Per block of range bins: the field on the source columns, then (formed) the beams' complex amplitudes,
    // into A: per bin, re of the N beams, then im.
    const int blocks = (K + kBlockRows - 1) / kBlockRows;
    std::vector<float> A = scratch::take<float>(size_t(K) * N * 2); // every value written below
    std::vector<double> unit(static_cast<size_t>(blocks));          // per block: A's unit amplitude
    tbb::parallel_for(0, blocks, [&](int block) {
        struct Scratch {
            std::vector<double> rise, reach;
            std::vector<std::uint32_t> key;
            std::vector<float> power, cos_phase, sin_phase, re, im, block_re, block_im;
        };
        thread_local Scratch w; // a leaf task's: nothing else runs on this thread while it is in use
        w.rise.resize(size_t(J)), w.reach.resize(size_t(J));
        for (auto* v : {&w.power, &w.cos_phase, &w.sin_phase, &w.re, &w.im}) v->resize(size_t(J));
        w.key.resize(size_t(J));
        w.block_re.resize(formed ? size_t(J) * kBlockRows : 0), w.block_im.resize(w.block_re.size());
        const int k0 = block * kBlockRows, rows = std::min(kBlockRows, K - k0);
        // In single precision relative to the block's strongest sample.
        const float top_db = max_level(size_t(rows) * J, src.level_db.data() + size_t(k0) * J);
        constexpr double kLog2Of10Over20 = 0.16609640474436812;
        unit[size_t(block)] = top_db == -std::numeric_limits<float>::infinity()
                                  ? 0.0
                                  : fast::exp2_nonpositive((double(top_db) - peak_db) * kLog2Of10Over20);
        if (unit[size_t(block)] == 0) { // nothing echoes in these bins: no field to draw
            std::fill(A.begin() + std::ptrdiff_t(size_t(k0) * N * 2),
                      A.begin() + std::ptrdiff_t(size_t(k0 + rows) * N * 2), 0.0f);
            return;
        }
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
                relative_field_row(J, level, top_db, w.power.data(), w.cos_phase.data(), w.sin_phase.data(),
                                   row, row + N);
                continue;
            }
            relative_field_row(J, level, top_db, w.power.data(), w.cos_phase.data(), w.sin_phase.data(),
                               w.re.data(), w.im.data());
            for (int j = 0; j < J; ++j) {
                w.block_re[size_t(j) * kBlockRows + size_t(t)] = w.re[size_t(j)];
                w.block_im[size_t(j) * kBlockRows + size_t(t)] = w.im[size_t(j)];
            }
        }
        if (formed)
            form_block(sums, N, w.block_re.data(), w.block_im.data(), rows, A.data() + size_t(k0) * N * 2);
    });

    // The matched filter along range on the amplitudes, then |.|^2.
    const SensorParams& p = s.sensor;
    const std::vector<double> g = range_amplitude_kernel(p.pulse, p.range_resolution_m, dr);
    std::vector<double> out = scratch::take<double>(size_t(K) * N); // every value written below
    tbb::parallel_for(tbb::blocked_range<int>(0, K, 16), [&](const tbb::blocked_range<int>& ks) {
        for (int k = ks.begin(); k < ks.end(); ++k)
            intensity_row(A.data(), unit.data(), K, N, k, g, out.data() + size_t(k) * N);
    });
    scratch::give(std::move(A));
    return out;
}

} // namespace sonarsim

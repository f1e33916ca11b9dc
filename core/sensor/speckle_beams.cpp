#include "core/sensor/speckle_beams.hpp"

#include "core/base/fast_math.hpp"
#include "core/base/recent_shared.hpp"
#include "core/grid/sensor_patterns.hpp"

#include <algorithm>
#include <cstring>
#ifdef __x86_64__
#include <immintrin.h>
#endif
#include <limits>

namespace sonarsim {
namespace {

constexpr int kGroupRows = kSpeckleGroupRows;

BeamSums by_beam(const AzimuthBeamforming& bf) {
    const int J = int(bf.first.size());
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

/// The beams of a group from its field (re of column j, row t at j * 2 kGroupRows + t, im kGroupRows further
/// on; 64-byte aligned, so that a column is whole cache lines): (re, im) of beam b for the group's row t into
/// out[t * 2 N + b] and out[t * 2 N + N + b], t < rows. The group's rows in vectors of W floats (GCC's vector
/// extension): W = 16 fills an AVX-512 register, 8 an AVX one, 4 an SSE one. kBeams beams are summed side by
/// side (each over its own columns in ascending order, as one at a time would), so that the adds of one do
/// not wait for another's; as many as the registers hold. With `intensity`, instead: |scale[t] (re, im)|^2
/// into intensity[t * N + b] (the output of a single-tap range filter, scale its weight times the row's
/// unit).
template <int W, int kBeams>
inline __attribute__((always_inline)) void form_group_lanes(const BeamSums& sums, int N, const float* field,
                                                            int rows, float* out, const double* scale,
                                                            double* intensity) {
    typedef float Lanes __attribute__((vector_size(W * sizeof(float))));
    constexpr int kParts = kGroupRows / W;
    struct Sum {
        Lanes re[kParts], im[kParts];
    };
    const int* start = sums.start.data();
    const int* column = sums.column.data();
    const float* weight = sums.weight.data();
    auto add_column = [&](Sum & sum, int p) __attribute__((always_inline)) {
        const float w = weight[p];
        const float* x_re = static_cast<const float*>(
            __builtin_assume_aligned(field + size_t(column[p]) * 2 * kGroupRows, 64));
        const float* x_im = x_re + kGroupRows;
        for (int h = 0; h < kParts; ++h) {
            Lanes a, c;
            std::memcpy(&a, x_re + h * W, sizeof a);
            std::memcpy(&c, x_im + h * W, sizeof c);
            sum.re[h] += w * a, sum.im[h] += w * c;
        }
    };
    auto store = [&](const Sum& sum, int b) __attribute__((always_inline)) {
        float beam_re[kGroupRows], beam_im[kGroupRows]; // the sums out of their registers
        std::memcpy(beam_re, sum.re, sizeof beam_re), std::memcpy(beam_im, sum.im, sizeof beam_im);
        if (!intensity) {
            for (int t = 0; t < rows; ++t)
                out[size_t(t) * 2 * N + size_t(b)] = beam_re[t],
                                        out[size_t(t) * 2 * N + size_t(N + b)] = beam_im[t];
            return;
        }
        double level[kGroupRows]; // |scale A|^2 as intensity_row has it with a single tap
        for (int t = 0; t < kGroupRows; ++t) {
            const double re = scale[t] * double(beam_re[t]), im = scale[t] * double(beam_im[t]);
            level[t] = re * re + im * im;
        }
        for (int t = 0; t < rows; ++t) intensity[size_t(t) * N + size_t(b)] = level[t];
    };
    int b = 0;
    for (; b + kBeams <= N; b += kBeams) {
        Sum sum[kBeams] = {};
        int p[kBeams], end[kBeams], common = std::numeric_limits<int>::max();
        for (int i = 0; i < kBeams; ++i)
            p[i] = start[b + i], end[i] = start[b + i + 1], common = std::min(common, end[i] - p[i]);
        for (int q = 0; q < common; ++q)
            for (int i = 0; i < kBeams; ++i) add_column(sum[i], p[i] + q);
        for (int i = 0; i < kBeams; ++i) {
            for (int q = p[i] + common; q < end[i]; ++q) add_column(sum[i], q);
            store(sum[i], b + i);
        }
    }
    for (; b < N; ++b) {
        Sum s0 = {};
        for (int p = start[b]; p < start[b + 1]; ++p) add_column(s0, p);
        store(s0, b);
    }
}

#ifdef SONARSIM_SIMD_DISPATCH
SONARSIM_AVX2_TARGET void form_group_avx2(const BeamSums& sums, int N, const float* field, int rows,
                                          float* out, const double* scale, double* intensity) {
    form_group_lanes<8, 2>(sums, N, field, rows, out, scale, intensity);
}
SONARSIM_AVX512_TARGET void form_group_avx512(const BeamSums& sums, int N, const float* field, int rows,
                                              float* out, const double* scale, double* intensity) {
    form_group_lanes<16, 4>(sums, N, field, rows, out, scale, intensity);
}
#endif

/// The field of a group by column (field[j * 2 kGroupRows + t] re, kGroupRows further on im) from its rows
/// (rows[t * 2 J + j] re, J further on im), a tile of 16 columns at a time.
SONARSIM_SIMD_CLONES void to_columns_plain(int J, const float* rows, float* field) {
    constexpr int kTile = 16;
    int j0 = 0;
    for (; j0 + kTile <= J; j0 += kTile)
        for (int part = 0; part < 2; ++part)
            for (int t = 0; t < kGroupRows; ++t) {
                const float* from = rows + size_t(t) * 2 * J + size_t(part) * J + size_t(j0);
                float* to = field + size_t(j0) * 2 * kGroupRows + size_t(part) * kGroupRows + size_t(t);
                for (int j = 0; j < kTile; ++j) to[size_t(j) * 2 * kGroupRows] = from[j];
            }
    for (; j0 < J; ++j0)
        for (int part = 0; part < 2; ++part)
            for (int t = 0; t < kGroupRows; ++t)
                field[size_t(j0) * 2 * kGroupRows + size_t(part) * kGroupRows + size_t(t)] =
                    rows[size_t(t) * 2 * J + size_t(part) * J + size_t(j0)];
}

#ifdef SONARSIM_SIMD_DISPATCH
/// to_columns_plain by 8 x 8 tiles transposed in AVX registers (whole vectors loaded and stored).
SONARSIM_AVX2_TARGET void to_columns_avx2(int J, const float* rows, float* field) {
    static_assert(kGroupRows % 8 == 0, "whole tiles of rows");
    int j0 = 0;
    for (; j0 + 8 <= J; j0 += 8)
        for (int part = 0; part < 2; ++part)
            for (int t0 = 0; t0 < kGroupRows; t0 += 8) {
                __m256 r[8], u[8], v[8];
                for (int i = 0; i < 8; ++i)
                    r[i] = _mm256_loadu_ps(rows + size_t(t0 + i) * 2 * J + size_t(part) * J + size_t(j0));
                for (int i = 0; i < 8; i += 2)
                    u[i] = _mm256_unpacklo_ps(r[i], r[i + 1]), u[i + 1] = _mm256_unpackhi_ps(r[i], r[i + 1]);
                for (int i = 0; i < 8; i += 4) {
                    v[i] = _mm256_shuffle_ps(u[i], u[i + 2], _MM_SHUFFLE(1, 0, 1, 0));
                    v[i + 1] = _mm256_shuffle_ps(u[i], u[i + 2], _MM_SHUFFLE(3, 2, 3, 2));
                    v[i + 2] = _mm256_shuffle_ps(u[i + 1], u[i + 3], _MM_SHUFFLE(1, 0, 1, 0));
                    v[i + 3] = _mm256_shuffle_ps(u[i + 1], u[i + 3], _MM_SHUFFLE(3, 2, 3, 2));
                }
                float* to = field + size_t(j0) * 2 * kGroupRows + size_t(part) * kGroupRows + size_t(t0);
                for (int c = 0; c < 4; ++c) { // column c from the low halves, column c + 4 from the high ones
                    _mm256_storeu_ps(to + size_t(c) * 2 * kGroupRows,
                                     _mm256_permute2f128_ps(v[c], v[c + 4], 0x20));
                    _mm256_storeu_ps(to + size_t(c + 4) * 2 * kGroupRows,
                                     _mm256_permute2f128_ps(v[c], v[c + 4], 0x31));
                }
            }
    for (; j0 < J; ++j0) // the last columns one at a time
        for (int part = 0; part < 2; ++part)
            for (int t = 0; t < kGroupRows; ++t)
                field[size_t(j0) * 2 * kGroupRows + size_t(part) * kGroupRows + size_t(t)] =
                    rows[size_t(t) * 2 * J + size_t(part) * J + size_t(j0)];
}
#endif

} // namespace

std::shared_ptr<const BeamSums> shared_beam_sums(const SceneDesc& s) {
    static RecentShared<std::shared_ptr<const AzimuthBeamforming>, BeamSums, 4> kept; // the pattern held
    const std::shared_ptr<const AzimuthBeamforming> bf = shared_azimuth_beamforming(s, true);
    return kept.get(bf, [&] { return std::make_shared<const BeamSums>(by_beam(*bf)); });
}

// form_group_lanes with the widest vectors the CPU has (the same sums either way).
void form_group(const BeamSums& sums, int N, const float* field, int rows, float* out, const double* scale,
                double* intensity) {
#ifdef SONARSIM_SIMD_DISPATCH
    static const bool avx512 = __builtin_cpu_supports("avx512f"), avx2 = __builtin_cpu_supports("avx2");
    if (avx512) return form_group_avx512(sums, N, field, rows, out, scale, intensity);
    if (avx2) return form_group_avx2(sums, N, field, rows, out, scale, intensity);
#endif
    form_group_lanes<4, 1>(sums, N, field, rows, out, scale, intensity);
}

// to_columns_plain, with AVX where the CPU has it (the same values moved).
void to_columns(int J, const float* rows, float* field) {
#ifdef SONARSIM_SIMD_DISPATCH
    static const bool avx2 = __builtin_cpu_supports("avx2");
    if (avx2) return to_columns_avx2(J, rows, field);
#endif
    to_columns_plain(J, rows, field);
}

} // namespace sonarsim

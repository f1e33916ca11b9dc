#include "core/sensor/keyed_variates.hpp"

#include "core/base/fast_math.hpp"

#include <cmath>
#include <vector>

namespace sonarsim::keyed {
namespace {

/// floor(y) for |y| < 2^51 in plain arithmetic: adding and subtracting 1.5 2^52 rounds to an integer.
inline double floor_small(double y) {
    constexpr double kRound = 6755399441055744.0;
    const double r = (y + kRound) - kRound;
    return r > y ? r - 1 : r;
}

/// floor(y) modulo 2^32, for |y| < 2^51. kFromBits: from the low bits of the mantissa of y + 1.5 2^52
/// (modulo 2^32 as two's complement, the offset 2^51 being a multiple of 2^32), less 1 where that rounded up;
/// otherwise in double arithmetic and one conversion to a 32-bit integer. The same value; the first is the
/// faster under AVX2, the second the one that vectorises with SSE2 alone.
template <bool kFromBits> inline std::uint32_t cell_index(double y) {
    constexpr double kRound = 6755399441055744.0;
    if (kFromBits) {
        const double t = y + kRound;
        return std::uint32_t(fast::bits_of(t)) - (t - kRound > y ? 1U : 0U);
    }
    const double n = floor_small(y);
    const double wrapped = n - 4294967296.0 * floor_small(n * (1.0 / 4294967296.0)); // [0, 2^32)
    return std::uint32_t(std::int32_t(wrapped - 2147483648.0)) ^ 0x80000000U;
}

/// A uniform variate in (0, 1] from the top 24 bits m of h: (m + 1/2) / 2^24, rounded to single precision.
inline float unit24(std::uint32_t h) {
    return (float(std::int32_t(h >> 8)) + 0.5f) * 0x1.0p-24f;
}

/// Marsaglia and Tsang's draw number `attempt` for `key` (d = a - 1/3, c = 1 / sqrt(9 d)): d v^3, and in
/// `accepted` whether the draw stands.
inline float gamma_attempt(std::uint32_t key, std::uint32_t attempt, float d, float c, bool& accepted) {
    const std::uint32_t h = mix32(key + attempt * 0x9e3779b9U);
    float cos_phase, sin_phase; // the sine unused
    fast::sincos_turn_f(unit24(mix32(h ^ 0x2545f491U)) - 0.5f, cos_phase, sin_phase);
    const float x = std::sqrt(-2 * fast::ln_f(unit24(h))) * cos_phase; // N(0, 1) by Box and Muller
    const float u = unit24(mix32(h + 0xb5297a4dU));
    const float w = 1 + c * x, v = w * w * w, x2 = x * x;
    accepted =
        (w > 0) & ((u < 1 - 0.0331f * x2 * x2) | (fast::ln_f(u) < 0.5f * x2 + d * (1 - v + fast::ln_f(v))));
    return d * v;
}

/// Every key's first draw.
SONARSIM_SIMD_CLONES void first_gamma_attempts(int n, const std::uint32_t* key, float d, float c, double* out,
                                               std::uint8_t* accepted) {
    for (int i = 0; i < n; ++i) {
        bool ok;
        out[i] = gamma_attempt(key[i], 0, d, c, ok);
        accepted[i] = ok;
    }
}

template <bool kFromBits>
inline __attribute__((always_inline)) void cell_keys(int n, const RaisedPoints& p, double inv_cell,
                                                     std::uint32_t seed, std::uint32_t* key) {
    const double ox = p.origin_m[0], oy = p.origin_m[1], oz = p.origin_m[2];
    const double ux = p.up[0], uy = p.up[1], uz = p.up[2];
    const double *rise = p.rise_m, *reach = p.reach_m, *ax = p.ahead_x, *ay = p.ahead_y, *az = p.ahead_z;
    for (int i = 0; i < n; ++i) {
        const double x = ox + rise[i] * ux + reach[i] * ax[i];
        const double y = oy + rise[i] * uy + reach[i] * ay[i];
        const double z = oz + rise[i] * uz + reach[i] * az[i];
        std::uint32_t h = mix32(seed + cell_index<kFromBits>(x * inv_cell));
        h = mix32(h + cell_index<kFromBits>(y * inv_cell));
        key[i] = mix32(h + cell_index<kFromBits>(z * inv_cell));
    }
}

#ifdef SONARSIM_SIMD_DISPATCH
SONARSIM_AVX2_TARGET void cell_keys_avx2(int n, const RaisedPoints& p, double inv_cell, std::uint32_t seed,
                                         std::uint32_t* key) {
    cell_keys<true>(n, p, inv_cell, seed, key);
}
SONARSIM_AVX512_TARGET void cell_keys_avx512(int n, const RaisedPoints& p, double inv_cell,
                                             std::uint32_t seed, std::uint32_t* key) {
    cell_keys<true>(n, p, inv_cell, seed, key);
}
#endif

} // namespace

void world_cell_keys(int n, const RaisedPoints& p, double inv_cell, std::uint32_t seed, std::uint32_t* key) {
#ifdef SONARSIM_SIMD_DISPATCH
    static const bool avx512 = __builtin_cpu_supports("avx512f"), avx2 = __builtin_cpu_supports("avx2");
    if (avx512) return cell_keys_avx512(n, p, inv_cell, seed, key);
    if (avx2) return cell_keys_avx2(n, p, inv_cell, seed, key);
#endif
    cell_keys<false>(n, p, inv_cell, seed, key);
}

SONARSIM_SIMD_CLONES void exp_phasors(int n, const std::uint32_t* key, float* power, float* cos_phase,
                                      float* sin_phase) {
    for (int i = 0; i < n; ++i) {
        power[i] = -fast::ln_f(unit24(mix32(key[i] ^ 0x5bd1e995U)));
        fast::sincos_turn_f(unit24(mix32(key[i] + 0x68e31da4U)) - 0.5f, cos_phase[i], sin_phase[i]);
    }
}

void gamma_unit_mean(int n, const std::uint32_t* key, double shape, double* out) {
    const double a = shape < 1 ? shape + 1 : shape, d = a - 1.0 / 3;
    const float df = float(d), cf = float(1 / std::sqrt(9 * d));
    thread_local std::vector<std::uint8_t> accepted; // used only within this call
    accepted.resize(size_t(n));
    first_gamma_attempts(n, key, df, cf, out, accepted.data());
    for (int i = 0; i < n; ++i) {
        // A few per cent of the draws are rejected: their keys' next draws, one at a time.
        for (std::uint32_t attempt = 1; !accepted[size_t(i)]; ++attempt) {
            bool ok;
            const float v = gamma_attempt(key[i], attempt, df, cf, ok);
            if (ok || attempt == 1000) out[i] = ok ? v : a, accepted[size_t(i)] = 1; // 1000: not reached
        }
    }
    if (shape < 1)
        for (int i = 0; i < n; ++i)
            out[i] *=
                fast::exp2_nonpositive(fast::log2_positive(unit24(mix32(key[i] ^ 0x1b873593U))) / shape);
    const double inv_shape = 1 / shape;
    for (int i = 0; i < n; ++i) out[i] *= inv_shape;
}

} // namespace sonarsim::keyed

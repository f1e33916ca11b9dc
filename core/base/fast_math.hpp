// Branch-free elementary functions for the per-cell loops of the sensor stage (hundreds of thousands of
// cells per frame): plain arithmetic, selects and bit moves, no tables, so that loops of them vectorise.
// Each is a polynomial on a reduced argument with its error bound stated; 2^x and log2 in double precision
// cover the whole double range, the single-precision ln and sincos the uniforms of the random variates.
#pragma once
#include <cmath>
#include <cstdint>
#include <cstring>

// On x86-64 (GCC), functions marked so get AVX-512 and AVX2 clones besides the baseline one, picked when the
// program loads. None fuses a product into a sum (no FMA: AVX-512 has it, and GCC would contract a * b + c
// there unless told not to), so all give the same bits. SONARSIM_AVX512_TARGET and SONARSIM_AVX2_TARGET: the
// same for functions dispatched by hand (__builtin_cpu_supports). Not under the sanitizers (their runtimes
// start after the clones are resolved).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_ADDRESS__) &&     \
    !defined(__SANITIZE_THREAD__)
#define SONARSIM_SIMD_CLONES                                                                                 \
    __attribute__((target_clones("avx512f", "avx2", "default"), optimize("fp-contract=off")))
#define SONARSIM_SIMD_DISPATCH 1
#define SONARSIM_AVX512_TARGET __attribute__((target("avx512f"), optimize("fp-contract=off")))
#define SONARSIM_AVX2_TARGET __attribute__((target("avx2")))
#else
#define SONARSIM_SIMD_CLONES
#endif

namespace sonarsim::fast {

/// The same bits as another type of the same size (C++20's std::bit_cast; a plain move, also inside
/// vectorised loops).
template <class To, class From> inline To bit_cast(const From& x) {
    static_assert(sizeof(To) == sizeof(From), "bit_cast between types of one size");
    To out;
    std::memcpy(&out, &x, sizeof out);
    return out;
}

/// The bits of a double, and a double from its bits.
inline std::uint64_t bits_of(double x) {
    return bit_cast<std::uint64_t>(x);
}
inline double double_of(std::uint64_t u) {
    return bit_cast<double>(u);
}

/// 2^x for x <= 0; 0 below -1022 (3077 dB below the reference) and for NaN. 2^n from the exponent bits (n the
/// nearest integer, found by adding and subtracting 1.5 2^52) times 2^f, |f| <= 1/2, by the Taylor series of
/// e^(f ln 2) to 12th order (truncation below 2e-16): relative error below 1e-15 (checked in the tests).
inline double exp2_nonpositive(double x) {
    constexpr double kRound = 6755399441055744.0, kTwo52 = 4503599627370496.0;
    const double xc = x < -1022.0 ? -1022.0 : x;
    const double n = (xc + kRound) - kRound, y = (xc - n) * 0.6931471805599453;
    double p = 1.0 / 479001600; // 1 / 12!, then Horner down to 1 / 0!
    p = p * y + 1.0 / 39916800, p = p * y + 1.0 / 3628800, p = p * y + 1.0 / 362880;
    p = p * y + 1.0 / 40320, p = p * y + 1.0 / 5040, p = p * y + 1.0 / 720, p = p * y + 1.0 / 120;
    p = p * y + 1.0 / 24, p = p * y + 1.0 / 6, p = p * y + 0.5, p = p * y + 1, p = p * y + 1;
    const double scale = double_of(bits_of(n + (1023.0 + kTwo52)) << 52); // 2^n
    return x >= -1022.0 ? scale * p : 0.0;
}

/// log2(x) for x > 0, denormals included. The exponent from the bits, plus ln(m) / ln 2 of the mantissa m in
/// [sqrt(1/2), sqrt 2) by the series 2 atanh(s), s = (m - 1) / (m + 1), |s| < 0.172, to s^21 (truncation
/// below 1e-17). Absolute error below 2e-15 plus an ulp of the result (2.3e-13 at the denormal end).
inline double log2_positive(double x) {
    constexpr double kTwo52 = 4503599627370496.0, kTwo64 = 18446744073709551616.0;
    const bool tiny = x < 2.2250738585072014e-308; // a denormal: scaled into the normal range first
    const std::uint64_t bits = bits_of(tiny ? x * kTwo64 : x);
    double e = double_of((bits >> 52) | 0x4330000000000000ULL) - (kTwo52 + 1023) - (tiny ? 64 : 0);
    double m = double_of((bits & 0x000fffffffffffffULL) | 0x3ff0000000000000ULL); // [1, 2)
    const bool high = m > 1.4142135623730951;
    m = high ? 0.5 * m : m;
    e += high ? 1 : 0;
    const double s = (m - 1) / (m + 1), s2 = s * s;
    double p = 1.0 / 21; // 1 / 21, then Horner down to 1 / 1
    p = p * s2 + 1.0 / 19, p = p * s2 + 1.0 / 17, p = p * s2 + 1.0 / 15, p = p * s2 + 1.0 / 13;
    p = p * s2 + 1.0 / 11, p = p * s2 + 1.0 / 9, p = p * s2 + 1.0 / 7, p = p * s2 + 1.0 / 5,
    p = p * s2 + 1.0 / 3;
    p = p * s2 + 1;
    return e + 2 * s * p * 1.4426950408889634;
}

/// The bits of a float, and a float from its bits.
inline std::int32_t bits_of(float x) {
    return bit_cast<std::int32_t>(x);
}
inline float float_of(std::int32_t i) {
    return bit_cast<float>(i);
}

/// ln(x) in single precision for normal x > 0, without branches (so a loop of it vectorises): the exponent
/// plus Cephes' logf polynomial of ln(1 + f) on the mantissa m = 1 + f in [sqrt(1/2), sqrt 2). Error
/// below 1.2e-7 max(1, |ln x|) on [2^-25, 1] (checked in the tests); zero, negative or denormal x give a
/// wrong value, not a trap.
inline float ln_f(float x) {
    const std::int32_t i = bits_of(x);
    std::int32_t e = (i >> 23) - 127;
    float m = float_of((i & 0x007fffff) | 0x3f800000); // [1, 2)
    const bool high = m > 1.41421356f;
    m = high ? 0.5f * m : m;
    e += high ? 1 : 0;
    const float f = m - 1, z = f * f, fe = float(e);
    float y = 7.0376836292e-2f;
    y = y * f - 1.1514610310e-1f;
    y = y * f + 1.1676998740e-1f;
    y = y * f - 1.2420140846e-1f;
    y = y * f + 1.4249322787e-1f;
    y = y * f - 1.6668057665e-1f;
    y = y * f + 2.0000714765e-1f;
    y = y * f - 2.4999993993e-1f;
    y = y * f + 3.3333331174e-1f;
    y = y * f * z - 2.12194440e-4f * fe - 0.5f * z;
    return f + y + 0.693359375f * fe;
}

/// 2^x in single precision for x <= 0; 0 below -126 and for NaN. 2^n from the exponent bits (n the nearest
/// integer, by adding and subtracting 1.5 2^23) times the Taylor series of e^(f ln 2), |f| <= 1/2, to 7th
/// order (truncation below 6e-9). Relative error below 3e-7 (checked in the tests).
inline float exp2_nonpositive_f(float x) {
    constexpr float kRound = 12582912.0f;
    const float xc = x < -126.0f ? -126.0f : x;
    const float n = (xc + kRound) - kRound, y = (xc - n) * 0.693147181f;
    float p = 1.0f / 5040;
    p = p * y + 1.0f / 720, p = p * y + 1.0f / 120, p = p * y + 1.0f / 24, p = p * y + 1.0f / 6;
    p = p * y + 0.5f, p = p * y + 1, p = p * y + 1;
    const float scale = float_of((std::int32_t(n) + 127) << 23); // 2^n
    return x >= -126.0f ? scale * p : 0.0f;
}

/// 10 log10(x) for x > 0, denormals included, to what a float level needs: the exponent from the bits, the
/// mantissa's logarithm in single precision (ln_f). Absolute error below 1e-6 dB (checked in the tests).
inline double db_level(double x) {
    constexpr double kTwo52 = 4503599627370496.0, kTwo64 = 18446744073709551616.0;
    const bool tiny = x < 2.2250738585072014e-308; // a denormal: scaled into the normal range first
    const std::uint64_t bits = bits_of(tiny ? x * kTwo64 : x);
    const double e = double_of((bits >> 52) | 0x4330000000000000ULL) - (kTwo52 + 1023) - (tiny ? 64 : 0);
    const float m = float(double_of((bits & 0x000fffffffffffffULL) | 0x3ff0000000000000ULL)); // [1, 2]
    return 3.0102999566398120 * e + 4.3429448190325183 * double(ln_f(m));
}

/// cos(2 pi t) and sin(2 pi t) in single precision for t in [-1/2, 1/2], without branches: reflected into
/// |2 pi t| <= pi / 2 (sin(pi - x) = sin x, cos(pi - x) = -cos x), then the Taylor series to x^12 and x^11
/// (truncation below 6e-8). Absolute error below 3e-7 (checked in the tests).
inline void sincos_turn_f(float t, float& c, float& s) {
    const bool flip = t > 0.25f || t < -0.25f;
    const float a = flip ? (t > 0 ? 0.5f : -0.5f) - t : t;
    const float x = 6.28318531f * a, x2 = x * x;
    float p = 1.0f / 479001600;
    p = p * x2 - 1.0f / 3628800;
    p = p * x2 + 1.0f / 40320;
    p = p * x2 - 1.0f / 720;
    p = p * x2 + 1.0f / 24;
    p = p * x2 - 0.5f;
    const float cos_a = p * x2 + 1;
    float q = -1.0f / 39916800;
    q = q * x2 + 1.0f / 362880;
    q = q * x2 - 1.0f / 5040;
    q = q * x2 + 1.0f / 120;
    q = q * x2 - 1.0f / 6;
    s = x + x * x2 * q;
    c = flip ? -cos_a : cos_a;
}

} // namespace sonarsim::fast

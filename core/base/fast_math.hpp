// Branch-light elementary functions for the per-cell loops of the sensor stage (hundreds of thousands of
// cells per frame). Each is a polynomial on a reduced argument with its error bound stated; none of them
// loses range: 2^x and log2 cover the whole normal double range.
#pragma once
#include <cmath>
#include <cstdint>
#include <cstring>

// On x86-64 (GCC), functions marked so get an AVX2 clone besides the baseline one, picked when the program
// loads; neither uses FMA, so both give the same bits. Not under the sanitizers (their runtimes start after
// the clones are resolved).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_ADDRESS__) &&     \
    !defined(__SANITIZE_THREAD__)
#define SONARSIM_AVX2_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define SONARSIM_AVX2_CLONES
#endif

namespace sonarsim::fast {

/// floor(x) as an integer for |x| < 2^62, without a libm call.
inline std::int64_t floor_int(double x) {
    const auto i = std::int64_t(x);
    return i - std::int64_t(x < double(i));
}

namespace detail {
/// log2 and the reciprocal of c_i = 1 + (i + 1/2) / 256, and cos, sin of 2 pi i / 1024: filled once at
/// start-up.
struct Tables {
    double log2c[256], invc[256], cos_t[1024], sin_t[1024], exp2_t[256];
    Tables() {
        for (int i = 0; i < 256; ++i) exp2_t[i] = std::exp2(i / 256.0);
        for (int i = 0; i < 256; ++i) {
            const double c = 1 + (i + 0.5) / 256;
            log2c[i] = std::log2(c), invc[i] = 1 / c;
        }
        for (int i = 0; i < 1024; ++i)
            cos_t[i] = std::cos(6.283185307179586 * i / 1024),
            sin_t[i] = std::sin(6.283185307179586 * i / 1024);
    }
};
inline const Tables tables;
} // namespace detail

/// 2^x for x <= 0; 0 below -1022 (3077 dB below the reference). 2^(n + j/256) from the exponent bits and a
/// table, times 2^f (f < 1/256) by its series to third order: relative error below 3e-12.
inline double exp2_nonpositive(double x) {
    if (!(x >= -1022.0)) return 0.0;
    const double t = x * 256;
    const std::int64_t k = floor_int(t); // x = k / 256 + f
    const double y = (t - double(k)) * (0.6931471805599453 / 256);
    const std::int64_t n = k >> 8; // floor(k / 256)
    const std::uint64_t bits = std::uint64_t(n + 1023) << 52;
    double scale;
    std::memcpy(&scale, &bits, sizeof scale);
    return scale * detail::tables.exp2_t[k & 255] * (1 + y * (1 + y * (0.5 + y / 6)));
}

/// log2(x) for x > 0 (denormals through std::log2). Absolute error below 2e-13 (the sum's rounding): log2 of
/// the mantissa's nearest table point c (its top 8 bits) plus the series of log2(1 + r), |r| = |m / c - 1| <
/// 1/512.
inline double log2_positive(double x) {
    if (x < 2.2250738585072014e-308) return std::log2(x);
    std::uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    const int e = int((bits >> 52) & 0x7ff) - 1023;
    const int i = int((bits >> 44) & 0xff);
    bits = (bits & 0x000fffffffffffffULL) | 0x3ff0000000000000ULL; // mantissa m in [1, 2)
    double m;
    std::memcpy(&m, &bits, sizeof m);
    const double r = m * detail::tables.invc[i] - 1;
    const double ln1p = r * (1 - r * (0.5 - r * (1.0 / 3 - r * 0.25)));
    return e + detail::tables.log2c[i] + ln1p * 1.4426950408889634;
}

/// 10 log10(x) for x > 0.
inline double db(double x) {
    return 3.0102999566398120 * log2_positive(x);
}

/// cos(2 pi u) for u in [0, 1]: the nearest of 1024 table angles and the Taylor series about it to third
/// order (|d| <= pi / 1024: error below 4e-12).
inline double cos_turn(double u) {
    const double t = u * 1024;
    const int i = int(t + 0.5);
    const double d = (t - i) * (6.283185307179586 / 1024);
    const double c = detail::tables.cos_t[i & 1023], s = detail::tables.sin_t[i & 1023];
    return c - d * (s + d * (0.5 * c - d * s / 6));
}

/// -ln(u) for u in (0, 1]: an Exp(1) variate from a uniform one.
inline double neg_ln(double u) {
    return -0.6931471805599453 * log2_positive(u);
}

/// The bits of a float, and a float from its bits (plain moves, also inside vectorised loops).
inline std::int32_t bits_of(float x) {
    std::int32_t i;
    std::memcpy(&i, &x, sizeof i);
    return i;
}
inline float float_of(std::int32_t i) {
    float x;
    std::memcpy(&x, &i, sizeof x);
    return x;
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

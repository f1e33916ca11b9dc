// Branch-light elementary functions for the per-cell loops of the sensor stage (hundreds of thousands of
// cells per frame). Each is a polynomial on a reduced argument with its error bound stated; none of them
// loses range: 2^x and log2 cover the whole normal double range.
#pragma once
#include <cmath>
#include <cstdint>
#include <cstring>

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

} // namespace sonarsim::fast

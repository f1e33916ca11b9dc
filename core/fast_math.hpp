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

/// 2^x for x <= 0; 0 below -1022 (3077 dB below the reference). Relative error below 1e-8.
inline double exp2_nonpositive(double x) {
    if (!(x >= -1022.0)) return 0.0;
    const std::int64_t n = floor_int(x + 0.5);
    const double y = (x - double(n)) * 0.6931471805599453; // in [-ln2/2, ln2/2]
    // e^y, Taylor to y^7: remainder below 0.347^8 / 8! < 5.5e-9.
    const double y2 = y * y;
    const double even = 1 + y2 * (0.5 + y2 * (1.0 / 24 + y2 * (1.0 / 720)));
    const double odd = y * (1 + y2 * (1.0 / 6 + y2 * (1.0 / 120 + y2 * (1.0 / 5040))));
    const std::uint64_t bits = std::uint64_t(n + 1023) << 52;
    double scale;
    std::memcpy(&scale, &bits, sizeof scale);
    return (even + odd) * scale;
}

/// log2(x) for x > 0 (denormals through std::log2). Absolute error below 1e-8.
inline double log2_positive(double x) {
    if (x < 2.2250738585072014e-308) return std::log2(x);
    std::uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    int e = int((bits >> 52) & 0x7ff) - 1023;
    bits = (bits & 0x000fffffffffffffULL) | 0x3ff0000000000000ULL; // mantissa m in [1, 2)
    double m;
    std::memcpy(&m, &bits, sizeof m);
    if (m > 1.4142135623730951) m *= 0.5, ++e; // m in [1/sqrt 2, sqrt 2): |t| <= 0.1716
    // ln m = 2 atanh t, t = (m - 1) / (m + 1); series to t^9: remainder below 2 t^11 / 11 < 7e-10.
    const double t = (m - 1) / (m + 1), t2 = t * t;
    const double s = 1 + t2 * (1.0 / 3 + t2 * (1.0 / 5 + t2 * (1.0 / 7 + t2 * (1.0 / 9))));
    return e + 2 * t * s * 1.4426950408889634;
}

/// 10 log10(x) for x > 0.
inline double db(double x) {
    return 3.0102999566398120 * log2_positive(x);
}

/// cos(2 pi u) for u in [0, 1]. Absolute error below 1e-8.
inline double cos_turn(double u) {
    // cos(2 pi u) = -cos(theta), theta = 2 pi (u - 1/2) in [-pi, pi]; fold to [0, pi/2] with the sign.
    double th = std::abs(6.283185307179586 * (u - 0.5)), sign = -1;
    if (th > 1.5707963267948966) th = 3.141592653589793 - th, sign = 1;
    const double t2 = th * th; // Taylor to th^12: remainder below (pi/2)^14 / 14! < 7e-9
    const double c =
        1 - t2 * (0.5 - t2 * (1.0 / 24 -
                              t2 * (1.0 / 720 - t2 * (1.0 / 40320 - t2 * (1.0 / 3628800 - t2 / 479001600)))));
    return sign * c;
}

/// -ln(u) for u in (0, 1], in single precision (absolute error below 1e-6): an Exp(1) variate from a
/// uniform one, where the variate's own randomness dwarfs the error.
inline float neg_ln(float u) {
    std::uint32_t bits;
    std::memcpy(&bits, &u, sizeof bits);
    int e = int((bits >> 23) & 0xff) - 127;
    bits = (bits & 0x007fffffU) | 0x3f800000U;
    float m;
    std::memcpy(&m, &bits, sizeof m);
    if (m > 1.41421356f) m *= 0.5f, ++e;
    const float t = (m - 1) / (m + 1), t2 = t * t; // |t| <= 0.1716: series to t^7, remainder < 3e-7
    const float ln_m = 2 * t * (1 + t2 * (1.0f / 3 + t2 * (1.0f / 5 + t2 * (1.0f / 7))));
    return -(float(e) * 0.69314718f + ln_m);
}

} // namespace sonarsim::fast

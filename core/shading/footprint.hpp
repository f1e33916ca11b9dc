// A cell's range footprint (the sum of its elevation and azimuth range extents on its hit plane) and how it
// spreads over range bins: shared by shading (shade.cpp) and the ground truth (ground_truth.cpp), so both
// see the same cells in the same bins.
#pragma once
#include "core/data/hits.hpp"

#include <algorithm>
#include <cmath>

namespace sonarsim::detail {

/// The largest change of a cell's echo per metre of range, relative, from its centre to either end of its
/// elevation extent that the linear trend of Footprint carries: the echo's trend is exponential (its slope
/// is d ln / d range), and 1 + x stays within 3 % of exp(x) up to x = 1/4. Steeper trends (a Lambert
/// exponent of 100, a specular lobe of 0.05 deg) are held there: at 1/2 or 1 the stiff cases and the
/// Oculus-class bench scene measured larger errors than with none.
constexpr double kMaxTrend = 0.25;

/// Sum of two independent uniforms U[a0, a1] + U[b0, b1] (the elevation and the azimuth extent): its
/// cumulative distribution (a trapezoid density). With a slope g [1/m], the first (elevation) uniform is
/// weighted by 1 + g (u - its centre), a linear trend of the echo across it, |g| w1 / 2 at most kMaxTrend;
/// its distribution is then piecewise cubic.
struct Footprint {
    double lo, p, q;               // support [lo, lo + p + q], p <= q the two widths
    double we = 0, wa = 0, g = 0;  // with a slope: the elevation and azimuth widths, the clamped slope
    double inv_we = 0, inv_wa = 0; // 1 / we, 1 / wa (0 when wa is): divisions once per cell
    Footprint(double a0, double a1, double b0, double b1, double slope = 0) {
        const double w1 = std::abs(a1 - a0), w2 = std::abs(b1 - b0);
        lo = std::min(a0, a1) + std::min(b0, b1);
        p = std::min(w1, w2), q = std::max(w1, w2);
        if (slope != 0 && w1 > 1e-6 * w2 && w1 > 0) {
            we = w1, wa = w2 > 1e-6 * w1 ? w2 : 0;
            inv_we = 1 / we, inv_wa = wa > 0 ? 1 / wa : 0;
            const double most = 2 * kMaxTrend * inv_we;
            g = std::clamp(slope, -most, most);
        }
    }
    double hi() const { return lo + p + q; }
    double cdf(double r) const { return g != 0 ? cdf_of<true>(r) : cdf_of<false>(r); }
    /// cdf() for a footprint known to have a trend (Tilted) or none.
    template <bool Tilted> double cdf_of(double r) const {
        const double x = r - lo;
        if (x <= 0) return 0;
        if (x >= p + q) return 1;
        if constexpr (Tilted) {
            return tilted_cdf(x);
        } else {
            if (p <= 1e-12 * q) return x / q; // a single uniform
            if (x < p) return x * x / (2 * p * q);
            if (x <= q) return p / (2 * q) + (x - p) / q;
            const double y = p + q - x;
            return 1 - y * y / (2 * p * q);
        }
    }

  private:
    /// cdf at lo + t with the slope: (1 / we) integral over the elevation part u in [0, we] of its weight
    /// w(u) = 1 + g (u - we / 2) times P(azimuth part <= t - u).
    double tilted_cdf(double t) const {
        const auto W = [&](double u) { return u + 0.5 * g * u * (u - we); };           // integral of w
        const auto M = [&](double u) { return u * u * (0.5 + g * (u / 3 - we / 4)); }; // of u w(u)
        const double u2 = std::min(t, we);
        if (wa == 0) return W(u2) * inv_we;
        const double u1 = std::clamp(t - wa, 0.0, we);
        return (W(u1) + (t * (W(u2) - W(u1)) - (M(u2) - M(u1))) * inv_wa) * inv_we;
    }
};

inline Footprint footprint_of(const Cell& c) {
    return Footprint(c.range_e_lo_m, c.range_e_hi_m, double(c.range_a_lo_m) - c.range_m,
                     double(c.range_a_hi_m) - c.range_m, c.spread_slope_per_m);
}

/// for_each_bin's walk over the bins of a footprint that spans some, with a trend (Tilted) or none: out of
/// line (measured on the floor scene: fewer instructions than with the even walk inlined).
template <bool Tilted, class F>
#if defined(__GNUC__)
[[gnu::noinline]]
#endif
void add_footprint_bins(const Footprint& f, int K, double r_min, double r_max, double dr, F& add) {
    const int b0 = int(std::clamp(std::floor((f.lo - r_min) / dr), 0.0, double(K)));
    const int b1 = int(std::clamp(std::floor((f.hi() - r_min) / dr), -1.0, double(K - 1)));
    // Bins wholly inside the trapezoid's flat top [lo + p, lo + q] each get dr / q: no cdf needed there
    // (long footprints at grazing incidence span tens of bins). With a trend along a longer elevation
    // extent, the top follows it: dr / q times the weight at the bin's centre less half the azimuth extent.
    const int flat_lo = int(std::clamp(std::ceil((f.lo + f.p - r_min) / dr), -1.0, double(K)));
    const int flat_hi =
        int(std::clamp(std::floor((f.lo + f.q - r_min) / dr), 0.0, double(K))) - 1; // last inside
    const double flat_share = dr / f.q;
    double c_prev = f.template cdf_of<Tilted>(r_min + b0 * dr);
    for (int b = b0; b <= b1; ++b) {
        if (b >= flat_lo && b <= flat_hi && b + 1 < K) {
            const int last = std::min({flat_hi, b1, K - 2});
            if (Tilted && f.we >= f.wa) {
                const double top_centre = f.lo + 0.5 * (f.we + f.wa) - r_min; // where the weight is 1
                double share = flat_share * (1 + f.g * ((b + 0.5) * dr - top_centre));
                const double step = flat_share * f.g * dr;
                for (; b <= last; ++b, share += step) add(b, share);
            } else {
                for (; b <= last; ++b) add(b, flat_share);
            }
            c_prev = f.template cdf_of<Tilted>(r_min + b * dr); // b: the first bin after the flat run
            --b;
            continue;
        }
        const double c_next = f.template cdf_of<Tilted>(b + 1 == K ? r_max : r_min + (b + 1) * dr);
        if (c_next > c_prev) add(b, c_next - c_prev);
        c_prev = c_next;
    }
}

/// Calls add(bin, fraction) for each range bin that receives part of the cell's echo.
template <class F>
void for_each_bin(const Cell& c, bool spread, int K, double r_min, double r_max, double dr, F&& add) {
    const Footprint f = footprint_of(c);
    if (!spread || f.p + f.q <= 1e-9 * dr) {
        const double b = std::floor(((spread ? f.lo : double(c.range_m)) - r_min) / dr);
        if (b >= 0 && b < K) add(int(b), 1.0);
        return;
    }
    if (f.g != 0)
        add_footprint_bins<true>(f, K, r_min, r_max, dr, add);
    else
        add_footprint_bins<false>(f, K, r_min, r_max, dr, add);
}

/// Elevation [rad] at which the cell's surface lies at range r: linear in range across its elevation
/// footprint, clamped to the cell.
inline double elevation_at(const Cell& c, double r) {
    const double span = double(c.range_e_hi_m) - c.range_e_lo_m;
    const double t = std::abs(span) > 1e-9 ? std::clamp((r - c.range_e_lo_m) / span, 0.0, 1.0) : 0.5;
    return c.elevation_rad + (t - 0.5) * c.elevation_width_rad;
}

} // namespace sonarsim::detail

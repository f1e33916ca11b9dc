#include "shade.hpp"

#include "pose.hpp"
#include "sensor_patterns.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tbb/parallel_for.h>

namespace sonarsim {
namespace {

constexpr double kLn10Over10 = 0.23025850929940458;
constexpr double kNegInf = -std::numeric_limits<double>::infinity();

/// Sum of two independent uniforms U[a0, a1] + U[b0, b1]: its cumulative distribution (a trapezoid density).
struct Footprint {
    double lo, p, q; // support [lo, lo + p + q], p <= q the two widths
    Footprint(double a0, double a1, double b0, double b1) {
        const double w1 = std::abs(a1 - a0), w2 = std::abs(b1 - b0);
        lo = std::min(a0, a1) + std::min(b0, b1);
        p = std::min(w1, w2), q = std::max(w1, w2);
    }
    double hi() const { return lo + p + q; }
    double cdf(double r) const {
        const double x = r - lo;
        if (x <= 0) return 0;
        if (x >= p + q) return 1;
        if (p <= 1e-12 * q) return x / q; // a single uniform
        if (x < p) return x * x / (2 * p * q);
        if (x <= q) return p / (2 * q) + (x - p) / q;
        const double y = p + q - x;
        return 1 - y * y / (2 * p * q);
    }
};

Footprint footprint_of(const Cell& c) {
    return Footprint(c.range_e_lo_m, c.range_e_hi_m, double(c.range_a_lo_m) - c.range_m,
                     double(c.range_a_hi_m) - c.range_m);
}

/// Log-domain accumulator: value = exp(m) * s.
struct LogSum {
    double m = kNegInf, s = 0;
    void add(double x) {
        if (x == kNegInf) return;
        if (x > m)
            s = s * std::exp(m - x) + 1, m = x;
        else
            s += std::exp(x - m);
    }
    double log_value() const { return s > 0 ? m + std::log(s) : kNegInf; }
};

} // namespace

const Material& material_of(const SceneDesc& s, unsigned m) {
    static const Material none{};
    if (m == 0) return s.seafloor ? s.seafloor->material : none;
    return s.objects.at(m - 1).material;
}

double cell_fraction_in(const Cell& c, SamplingScheme scheme, double r0, double r1) {
    if (scheme == SamplingScheme::Uniform) return (c.range_m >= r0 && c.range_m < r1) ? 1.0 : 0.0;
    const Footprint f = footprint_of(c);
    if (f.p + f.q <= 1e-9 * (r1 - r0)) return (f.lo >= r0 && f.lo < r1) ? 1.0 : 0.0;
    return f.cdf(r1) - f.cdf(r0);
}

namespace {

/// Calls add(bin, fraction) for each range bin that receives part of the cell's echo.
template <class F>
void for_each_bin(const Cell& c, bool spread, int K, double r_min, double r_max, double dr, F&& add) {
    const Footprint f = footprint_of(c);
    if (!spread || f.p + f.q <= 1e-9 * dr) {
        const double b = std::floor(((spread ? f.lo : double(c.range_m)) - r_min) / dr);
        if (b >= 0 && b < K) add(int(b), 1.0);
        return;
    }
    const int b0 = int(std::clamp(std::floor((f.lo - r_min) / dr), 0.0, double(K)));
    const int b1 = int(std::clamp(std::floor((f.hi() - r_min) / dr), -1.0, double(K - 1)));
    // Bins wholly inside the trapezoid's flat top [lo + p, lo + q] each get dr / q: no cdf needed there
    // (long footprints at grazing incidence span tens of bins).
    const int flat_lo = int(std::clamp(std::ceil((f.lo + f.p - r_min) / dr), -1.0, double(K)));
    const int flat_hi =
        int(std::clamp(std::floor((f.lo + f.q - r_min) / dr), 0.0, double(K))) - 1; // last inside
    const double flat_share = dr / f.q;
    double c_prev = f.cdf(r_min + b0 * dr);
    for (int b = b0; b <= b1; ++b) {
        if (b >= flat_lo && b <= flat_hi && b + 1 < K) {
            const int last = std::min({flat_hi, b1, K - 2});
            for (; b <= last; ++b) add(b, flat_share);
            c_prev = f.cdf(r_min + b * dr); // b: the first bin after the flat run
            --b;
            continue;
        }
        const double c_next = f.cdf(b + 1 == K ? r_max : r_min + (b + 1) * dr);
        if (c_next > c_prev) add(b, c_next - c_prev);
        c_prev = c_next;
    }
}

} // namespace

PolarImage shade(const TraceResult& hits, const SceneDesc& s) {
    const ShadeConstants k = shade_constants(s);
    const int K = s.sonar.range_bins, N = s.sonar.beams;
    const double r_min = s.sonar.range_min_m, r_max = s.sonar.range_max_m, dr = (r_max - r_min) / K;
    const bool spread = s.sampling.scheme != SamplingScheme::Uniform;

    PolarImage img;
    img.bins = K, img.beams = N;
    img.level_db.assign(size_t(K) * size_t(N), -std::numeric_limits<float>::infinity());
    tbb::parallel_for(0, std::min(N, hits.beams), [&](int i) {
        const auto& cells = hits.cells[size_t(i)];
        // Each cell's level (natural-log units), then a linear sum scaled by the beam's peak: one exp per
        // cell.
        std::vector<double> x(cells.size());
        double x_max = kNegInf;
        for (size_t n = 0; n < cells.size(); ++n) {
            const Cell& c = cells[n];
            x[n] = cell_echo_db(k, material_of(s, c.material), c.range_m, c.cos_incidence, c.solid_angle_sr) *
                   kLn10Over10;
            if (std::isnan(x[n])) x[n] = kNegInf;
            x_max = std::max(x_max, x[n]);
        }
        if (x_max == kNegInf) return;
        std::vector<double> lin(static_cast<size_t>(K), 0.0);
        std::vector<char> hit(static_cast<size_t>(K), 0);
        for (size_t n = 0; n < cells.size(); ++n) {
            if (x[n] == kNegInf) continue;
            const double w = std::exp(x[n] - x_max);
            for_each_bin(cells[n], spread, K, r_min, r_max, dr, [&](int b, double frac) {
                lin[size_t(b)] += w * frac;
                hit[size_t(b)] = 1;
            });
        }
        bool underflow = false;
        for (int b = 0; b < K; ++b) underflow |= hit[size_t(b)] && !(lin[size_t(b)] > 0);
        if (underflow) {
            // Some bin lies more than ~3000 dB below the beam's peak: sum that beam in the log domain
            // instead.
            std::vector<LogSum> acc(static_cast<size_t>(K));
            for (size_t n = 0; n < cells.size(); ++n)
                if (x[n] != kNegInf)
                    for_each_bin(cells[n], spread, K, r_min, r_max, dr,
                                 [&](int b, double frac) { acc[size_t(b)].add(x[n] + std::log(frac)); });
            for (int b = 0; b < K; ++b) {
                const double lv = acc[size_t(b)].log_value();
                if (lv != kNegInf)
                    img.level_db[size_t(b) * N + i] = float(lv / kLn10Over10 - k.noise_level_db);
            }
            return;
        }
        for (int b = 0; b < K; ++b)
            if (lin[size_t(b)] > 0)
                img.level_db[size_t(b) * N + i] =
                    float((x_max + std::log(lin[size_t(b)])) / kLn10Over10 - k.noise_level_db);
    });
    return img;
}

bool needs_sensor_inputs(const SceneDesc& s) {
    return azimuth_subcolumns(s) > 1 || s.sensor.speckle != Speckle::Off;
}

SensorInputs shade_sensor_inputs(const TraceResult& hits, const SceneDesc& s) {
    const ShadeConstants k = shade_constants(s);
    const int K = s.sonar.range_bins, N = s.sonar.beams, S = azimuth_subcolumns(s);
    const double r_min = s.sonar.range_min_m, r_max = s.sonar.range_max_m, dr = (r_max - r_min) / K;
    const double theta = deg2rad(s.sonar.azimuth_fov_deg), spacing = theta / N;
    const bool spread = s.sampling.scheme != SamplingScheme::Uniform;
    const bool fine = S > 1, elevation = s.sensor.speckle != Speckle::Off;
    const float nan = std::numeric_limits<float>::quiet_NaN();

    SensorInputs in;
    in.sub = S;
    if (fine) {
        in.fine.bins = K, in.fine.beams = N * S;
        in.fine.level_db.assign(size_t(K) * size_t(N) * S, -std::numeric_limits<float>::infinity());
    }
    if (elevation) in.elevation_rad.assign(size_t(K) * size_t(N), nan);
    tbb::parallel_for(0, std::min(N, hits.beams), [&](int i) {
        const auto& cells = hits.cells[size_t(i)];
        std::vector<double> x(cells.size());
        double x_max = kNegInf;
        for (size_t n = 0; n < cells.size(); ++n) {
            const Cell& c = cells[n];
            x[n] = cell_echo_db(k, material_of(s, c.material), c.range_m, c.cos_incidence, c.solid_angle_sr) *
                   kLn10Over10;
            if (std::isnan(x[n])) x[n] = kNegInf;
            x_max = std::max(x_max, x[n]);
        }
        if (x_max == kNegInf) return;
        const double a_top = theta / 2 - i * spacing; // the beam's port edge
        std::vector<double> lin(fine ? size_t(K) * S : 0, 0.0), wsum(elevation ? size_t(K) : 0, 0.0),
            esum(elevation ? size_t(K) : 0, 0.0);
        std::vector<double> share(size_t(S), 1.0);
        for (size_t n = 0; n < cells.size(); ++n) {
            if (x[n] == kNegInf) continue;
            const Cell& c = cells[n];
            const double w = std::exp(x[n] - x_max);
            if (fine) { // the cell's azimuth interval over the beam's sub-columns
                const double a0 = c.azimuth_rad - 0.5 * c.azimuth_width_rad, a1 = a0 + c.azimuth_width_rad;
                for (int q = 0; q < S; ++q) {
                    const double hi = a_top - q * spacing / S, lo = hi - spacing / S;
                    share[size_t(q)] =
                        std::max(0.0, std::min(a1, hi) - std::max(a0, lo)) / c.azimuth_width_rad;
                }
            }
            const double e_lo = c.elevation_rad - 0.5 * c.elevation_width_rad, de = c.elevation_width_rad;
            const double span = double(c.range_e_hi_m) - c.range_e_lo_m;
            for_each_bin(c, spread, K, r_min, r_max, dr, [&](int b, double frac) {
                const double v = w * frac;
                if (fine)
                    for (int q = 0; q < S; ++q) lin[size_t(b) * S + q] += v * share[size_t(q)];
                if (elevation) {
                    const double r = r_min + (b + 0.5) * dr;
                    const double t =
                        std::abs(span) > 1e-9 ? std::clamp((r - c.range_e_lo_m) / span, 0.0, 1.0) : 0.5;
                    wsum[size_t(b)] += v, esum[size_t(b)] += v * (e_lo + t * de);
                }
            });
        }
        for (int b = 0; b < K; ++b) {
            if (elevation && wsum[size_t(b)] > 0)
                in.elevation_rad[size_t(b) * N + i] = float(esum[size_t(b)] / wsum[size_t(b)]);
            for (int q = 0; fine && q < S; ++q)
                if (const double v = lin[size_t(b) * S + q]; v > 0)
                    in.fine.level_db[size_t(b) * N * S + size_t(i) * S + q] =
                        float((x_max + std::log(v)) / kLn10Over10 - k.noise_level_db);
        }
    });
    return in;
}

} // namespace sonarsim

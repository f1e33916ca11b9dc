#include "shade.hpp"

#include "footprint.hpp"
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
    const detail::Footprint f = detail::footprint_of(c);
    if (f.p + f.q <= 1e-9 * (r1 - r0)) return (f.lo >= r0 && f.lo < r1) ? 1.0 : 0.0;
    return f.cdf(r1) - f.cdf(r0);
}

double cell_levels(const std::vector<Cell>& cells, const SceneDesc& s, const ShadeConstants& k,
                   std::vector<double>& x) {
    x.resize(cells.size());
    double x_max = kNegInf;
    for (size_t n = 0; n < cells.size(); ++n) {
        const Cell& c = cells[n];
        x[n] = cell_echo_db(k, material_of(s, c.material), c.range_m, c.cos_incidence, c.solid_angle_sr) *
               kLn10Over10;
        if (std::isnan(x[n])) x[n] = kNegInf;
        x_max = std::max(x_max, x[n]);
    }
    return x_max;
}

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
        // Each cell's level, then a linear sum scaled by the beam's peak: one exp per cell.
        std::vector<double> x;
        const double x_max = cell_levels(cells, s, k, x);
        if (x_max == kNegInf) return;
        std::vector<double> lin(static_cast<size_t>(K), 0.0);
        std::vector<char> hit(static_cast<size_t>(K), 0);
        for (size_t n = 0; n < cells.size(); ++n) {
            if (x[n] == kNegInf) continue;
            const double w = std::exp(x[n] - x_max);
            detail::for_each_bin(cells[n], spread, K, r_min, r_max, dr, [&](int b, double frac) {
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
                    detail::for_each_bin(cells[n], spread, K, r_min, r_max, dr, [&](int b, double frac) {
                        acc[size_t(b)].add(x[n] + std::log(frac));
                    });
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
        std::vector<double> x;
        const double x_max = cell_levels(cells, s, k, x);
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
            detail::for_each_bin(c, spread, K, r_min, r_max, dr, [&](int b, double frac) {
                const double v = w * frac;
                if (fine)
                    for (int q = 0; q < S; ++q) lin[size_t(b) * S + q] += v * share[size_t(q)];
                if (elevation)
                    wsum[size_t(b)] += v,
                        esum[size_t(b)] += v * detail::elevation_at(c, r_min + (b + 0.5) * dr);
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

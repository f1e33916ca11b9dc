#include "core/shading/shade.hpp"

#include "core/shading/footprint.hpp"
#include "core/geometry/geometry.hpp"
#include "core/base/pose.hpp"
#include "core/sensor/sensor_patterns.hpp"

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
    if (m == kFloorMaterial) return s.seafloor ? s.seafloor->material : none;
    if (m == kSurfaceMaterial) return s.water.surface_material;
    return s.objects.at(m - 1).material;
}

double cell_fraction_in(const Cell& c, EchoBinning binning, double r0, double r1) {
    if (binning == EchoBinning::Point) return (c.range_m >= r0 && c.range_m < r1) ? 1.0 : 0.0;
    const detail::Footprint f = detail::footprint_of(c);
    if (f.p + f.q <= 1e-9 * (r1 - r0)) return (f.lo >= r0 && f.lo < r1) ? 1.0 : 0.0;
    return f.cdf(r1) - f.cdf(r0);
}

double reflection_gain_db(const ShadeConstants& k, const SceneDesc& s, unsigned m, double cos_inc) {
    if (m != kSurfaceMaterial) return -material_of(s, m).reflection_db;
    const double g = 2 * k.wavenumber_rad_per_m * s.water.surface_roughness_m * cos_inc; // Rayleigh parameter
    return -2 * g * g / kLn10Over10; // 10 log10 exp(-2 g^2)
}

double ghost_echo_db(const ShadeConstants& k, const SceneDesc& s, const GhostCell& g) {
    const Cell& c = g.cell;
    const double cos_in = std::min(1.0, double(c.cos_incidence)),
                 cos_out = std::min(1.0, double(g.cos_other));
    if (!(c.range_m > 0) || !(cos_in > 0) || !(c.solid_angle_sr > 0) || !(g.other_leg_m > 0)) return kNegInf;
    const Material& m = material_of(s, c.material);
    double bs = 0;
    if (!g.mixed()) {
        bs = backscatter_db(m, cos_in);
    } else {
        if (!(cos_out > 0)) return kNegInf;
        bs = m.nu_db + (m.q == 0 ? 0.0 : 0.5 * m.q * (std::log(cos_in) + std::log(cos_out)) / kLn10Over10);
    }
    double refl = 0;
    for (int j = 0; j < g.mirrors(); ++j)
        refl += (g.mixed() ? 1 : 2) * reflection_gain_db(k, s, g.mirror_material[j], g.mirror_cos[j]);
    return k.source_level_db - 2.0 * k.alpha_db_per_m * c.range_m - 20.0 * std::log10(double(g.other_leg_m)) +
           std::log(c.solid_angle_sr / cos_in) / kLn10Over10 + bs + refl;
}

BeamContributions::BeamContributions(const TraceResult& hits, int beam)
    : cells_(hits.cells[size_t(beam)]),
      ghosts_(size_t(beam) < hits.ghosts.size() ? &hits.ghosts[size_t(beam)] : nullptr) {}

double contribution_levels(const BeamContributions& beam, const SceneDesc& s, const ShadeConstants& k,
                           std::vector<double>& x) {
    x.resize(beam.size());
    double x_max = kNegInf;
    for (size_t n = 0; n < beam.size(); ++n) {
        const Cell& c = beam[n];
        const GhostCell* g = beam.ghost(n);
        x[n] =
            (g ? ghost_echo_db(k, s, *g)
               : cell_echo_db(k, material_of(s, c.material), c.range_m, c.cos_incidence, c.solid_angle_sr)) *
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
    const bool spread = s.sampling.binning == EchoBinning::Footprint;

    PolarImage img;
    img.bins = K, img.beams = N;
    img.level_db.assign(size_t(K) * size_t(N), -std::numeric_limits<float>::infinity());
    tbb::parallel_for(0, std::min(N, hits.beams), [&](int i) {
        const BeamContributions cells(hits, i);
        // Each cell's level, then a linear sum scaled by the beam's peak: one exp per cell.
        std::vector<double> x;
        const double x_max = contribution_levels(cells, s, k, x);
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

std::vector<double> path_order_energy_db(const TraceResult& hits, const SceneDesc& s) {
    const ShadeConstants k = shade_constants(s);
    const int K = s.sonar.range_bins, N = std::min(s.sonar.beams, hits.beams);
    const double r_min = s.sonar.range_min_m, r_max = s.sonar.range_max_m, dr = (r_max - r_min) / K;
    const bool spread = s.sampling.binning == EchoBinning::Footprint;
    const size_t orders = size_t(2 * std::max(0, s.sampling.bounces) + 1);
    std::vector<std::vector<LogSum>> per_beam(static_cast<size_t>(N), std::vector<LogSum>(orders));
    tbb::parallel_for(0, N, [&](int i) {
        const BeamContributions cells(hits, i);
        std::vector<double> x;
        contribution_levels(cells, s, k, x);
        for (size_t n = 0; n < cells.size(); ++n) {
            if (x[n] == kNegInf) continue;
            double inside = 0;
            detail::for_each_bin(cells[n], spread, K, r_min, r_max, dr, [&](int, double f) { inside += f; });
            const GhostCell* g = cells.ghost(n);
            const size_t order = std::min(orders - 1, size_t(g ? g->order() : 0));
            if (inside > 0) per_beam[size_t(i)][order].add(x[n] + std::log(inside));
        }
    });
    std::vector<double> out(orders);
    for (size_t o = 0; o < orders; ++o) {
        LogSum total;
        for (auto& b : per_beam)
            if (b[o].s > 0) total.add(b[o].log_value());
        out[o] = total.log_value() / kLn10Over10;
    }
    return out;
}

bool needs_sensor_inputs(const SceneDesc& s) {
    return azimuth_subcolumns(s) > 1 || s.sensor.speckle != Speckle::Off;
}

SensorInputs shade_sensor_inputs(const TraceResult& hits, const SceneDesc& s) {
    const ShadeConstants k = shade_constants(s);
    const int K = s.sonar.range_bins, N = s.sonar.beams, S = azimuth_subcolumns(s);
    const double r_min = s.sonar.range_min_m, r_max = s.sonar.range_max_m, dr = (r_max - r_min) / K;
    const double theta = deg2rad(s.sonar.azimuth_fov_deg), spacing = theta / N;
    const bool spread = s.sampling.binning == EchoBinning::Footprint;
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
        const BeamContributions cells(hits, i);
        std::vector<double> x;
        const double x_max = contribution_levels(cells, s, k, x);
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

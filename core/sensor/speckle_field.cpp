#include "core/sensor/speckle_field.hpp"

#include "core/base/fast_math.hpp"
#include "core/sensor/sensor.hpp"
#include "core/scene/sonar_grid.hpp"
#include "core/sensor/sensor_patterns.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <tbb/parallel_for.h>

namespace sonarsim {
namespace {

/// A uniform variate in (0, 1) from the top 32 bits of h.
double unit(std::uint64_t h) {
    return (double(h >> 32) + 0.5) * 0x1.0p-32;
}

} // namespace

WorldKeyGrid::WorldKeyGrid(std::uint64_t seed, double cell_m) {
    const int q_exp = int(std::floor(std::log2(0.5 * cell_m)));
    inv_q_ = std::ldexp(1.0, -q_exp);
    row_key_ = mix64(seed ^ std::uint64_t(std::int64_t(q_exp)));
}

SonarFrame::SonarFrame(const SceneDesc& s)
    : origin(to_glm(s.sonar.pose.position_m)), R(rotation_matrix(s.sonar.pose.orientation_deg)) {
    up = R * glm::dvec3(0, 0, 1);
}

glm::dvec3 SonarFrame::ahead(double a) const {
    return R * glm::dvec3(std::cos(a), std::sin(a), 0);
}

void convolve_range(std::vector<double>& rows, int K, int width, const std::vector<double>& h) {
    const int half = int(h.size() / 2);
    std::vector<double> out(rows.size(), 0.0);
    tbb::parallel_for(0, K, [&](int k) {
        double* o = out.data() + size_t(k) * width;
        for (int t = -half; t <= half; ++t) {
            const int src = k - t;
            if (src < 0 || src >= K) continue;
            const double w = h[size_t(t + half)];
            const double* x = rows.data() + size_t(src) * width;
            for (int b = 0; b < width; ++b) o[b] += w * x[b];
        }
    });
    rows.swap(out);
}

std::vector<double> form_speckle(const std::vector<double>& I, int K, int J, const SensorInputs& in,
                                 const SceneDesc& s) {
    const std::shared_ptr<const SonarGrid> sg = sonar_grid(s.sonar);
    const int N = sg->beams, S = J / N;
    const double r_min = sg->range_min_m, dr = sg->bin_m;
    const double column = sg->fov_rad / J; // the mean column's width [rad]
    const SonarFrame frame(s);
    std::vector<glm::dvec3> ahead(static_cast<size_t>(J));
    for (int j = 0; j < J; ++j) ahead[size_t(j)] = frame.ahead(sg->column_azimuth_rad(j, S));
    const bool formed = s.sensor.azimuth_window != AzimuthWindow::None;
    const AzimuthBeamforming bf = formed ? make_azimuth_beamforming(s, true) : AzimuthBeamforming{};
    std::vector<double> w2(2 * bf.amplitude.size()); // each weight twice: (re, im) pairs in one step
    for (size_t i = 0; i < bf.amplitude.size(); ++i) w2[2 * i] = w2[2 * i + 1] = bf.amplitude[i];
    const std::uint64_t seed = mix64(std::uint64_t(s.sensor.seed) ^ 0x677261696eULL); // "grain"

    // Per range bin: the field on the source columns, then (formed) the beams' complex amplitudes.
    std::vector<double> beams(size_t(K) * N * 2, 0.0); // (re, im) per (bin, beam)
    tbb::parallel_for(0, K, [&](int k) {
        const double r = r_min + (k + 0.5) * dr;
        const WorldKeyGrid grid(seed, std::min(dr, r * column));
        std::vector<double> local(formed ? size_t(J) * 2 : 0);
        double* field = formed ? local.data() : beams.data() + size_t(k) * N * 2;
        const double* x = I.data() + size_t(k) * J;
        const float* elevation = in.elevation_rad.data() + size_t(k) * N;
        glm::dvec3 base{};
        double scale = 0;
        for (int j = 0; j < J; ++j) {
            if (j % S == 0) std::tie(base, scale) = frame.raised(r, elevation[j / S]); // the beam's elevation
            if (x[j] == 0) {
                field[2 * j] = field[2 * j + 1] = 0;
                continue;
            }
            const std::uint64_t h = grid(base + scale * ahead[size_t(j)]);
            const double a = std::sqrt(x[j] * fast::neg_ln(unit(h))), u = unit(h << 32);
            field[2 * j] = a * fast::cos_turn(u), field[2 * j + 1] = a * fast::cos_turn(u + 0.75);
        }
        if (!formed) return;
        double* row = beams.data() + size_t(k) * N * 2;
        for (int j = 0; j < J; ++j) {
            const double re = field[2 * j], im = field[2 * j + 1];
            if (re == 0 && im == 0) continue;
            const double* w = w2.data() + 2 * bf.offset[size_t(j)];
            double* o = row + 2 * bf.first[size_t(j)];
            for (int u = 0, n = 2 * bf.count[size_t(j)]; u < n; u += 2)
                o[u] += w[u] * re, o[u + 1] += w[u + 1] * im; // one (re, im) pair a step
        }
    });
    const SensorParams& p = s.sensor;
    if (const std::vector<double> g = range_amplitude_kernel(p.pulse, p.range_resolution_m, dr); g.size() > 1)
        convolve_range(beams, K, 2 * N, g);
    std::vector<double> out(size_t(K) * N);
    for (size_t c = 0; c < out.size(); ++c)
        out[c] = beams[2 * c] * beams[2 * c] + beams[2 * c + 1] * beams[2 * c + 1];
    return out;
}

} // namespace sonarsim

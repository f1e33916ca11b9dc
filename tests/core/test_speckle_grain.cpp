// Speckle with the device's grain against closed forms. The field is circular complex Gaussian, formed
// linearly through the receive pattern's amplitude AF and the matched filter's amplitude h, so two outputs
// are jointly complex Gaussian and their intensities correlate as |E[A_1 A_2*]|^2 / (E|A_1|^2 E|A_2|^2)
// (Siegert). On a floor (scatterers of locally uniform strength, independent across the field's samples)
// that is, across beams b and b + 1 of a lens (axes Delta apart, the same pattern),
//   rho_beams = (integral AF(x) AF(x - Delta/w) dx)^2 / (integral AF(x)^2 dx)^2,
// the issue's |integral P(theta) P(theta - Delta) dtheta|^2 / (integral P^2)^2 with P the amplitude pattern,
// and along range (bins dr apart, cw amplitude h the triangle 1 - |x| / dr_res, a = dr / dr_res <= 1)
//   rho_range = (R(a) / R(0))^2, R(a) = integral h(x) h(x - a) dx = 2/3 - a^2 + a^3/2.
#include "support.hpp"

#include "core/pipeline/simulator.hpp"
#include "core/scene/params.hpp"
#include "core/scene/scene_io.hpp"
#include "core/grid/sensor_patterns.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <functional>

using namespace sonarsim;

namespace {

/// A flat floor filling a 60 deg, 256-beam fan; only the effects a test turns on.
SceneDesc grain_floor() {
    SceneDesc s = default_scene();
    s.objects.clear();
    s.sonar.pose.position_m = {0, 0, 1}, s.sonar.pose.orientation_deg = {0, 30, 0};
    s.sonar.azimuth_fov_deg = 60, s.sonar.beams = 256, s.sonar.range_bins = 1024;
    return s;
}

/// Speckle multipliers m = speckled / speckle-free (the same sensor with speckle off), per (bin, beam),
/// where the floor is locally uniform (the closed forms assume it): NaN unless the ideal image is finite
/// and within 1 dB of the cell's over +-3 bins and +-6 beams, and within `margin` beams of the fan's edges.
struct Multipliers {
    int bins, beams;
    std::vector<double> m;
    double at(int k, int b) const { return m[size_t(k) * size_t(beams) + size_t(b)]; }
};

Multipliers multipliers(SceneDesc s, int margin) {
    s.sensor.noise = false, s.sensor.tvg = Tvg::Off, s.sensor.gain_db = 0;
    const auto speckled = Simulator(s).render();
    s.sensor.speckle = Speckle::Off;
    const auto mean = Simulator(s).render();
    const PolarImage& ideal = mean->ideal();
    Multipliers r{s.sonar.range_bins, s.sonar.beams, {}};
    r.m.assign(mean->polar().level_db.size(), std::nan(""));
    auto uniform = [&](int k, int b) {
        for (int dk = -3; dk <= 3; ++dk)
            for (int db = -6; db <= 6; ++db) {
                if (k + dk < 0 || k + dk >= r.bins) return false;
                const float v = ideal.at(k + dk, b + db);
                if (!std::isfinite(v) || std::abs(v - ideal.at(k, b)) > 1) return false;
            }
        return true;
    };
    for (int k = 0; k < r.bins; ++k)
        for (int b = std::max(margin, 6); b < r.beams - std::max(margin, 6); ++b)
            if (uniform(k, b)) {
                const size_t c = size_t(k) * size_t(r.beams) + size_t(b);
                r.m[c] = test::lin(speckled->polar().level_db[c]) / test::lin(mean->polar().level_db[c]);
            }
    return r;
}

/// Pearson correlation of m at (k, b) and (k + dk, b + db) over the pairs where both are present.
double correlation(const Multipliers& x, int dk, int db) {
    double s1 = 0, s2 = 0, s11 = 0, s22 = 0, s12 = 0, n = 0;
    for (int k = 0; k + dk < x.bins; ++k)
        for (int b = 0; b + db < x.beams; ++b) {
            const double p = x.at(k, b), q = x.at(k + dk, b + db);
            if (std::isnan(p) || std::isnan(q)) continue;
            s1 += p, s2 += q, s11 += p * p, s22 += q * q, s12 += p * q, ++n;
        }
    const double cov = s12 / n - s1 / n * s2 / n;
    return cov / std::sqrt((s11 / n - s1 / n * s1 / n) * (s22 / n - s2 / n * s2 / n));
}

/// Mean and contrast (std / mean) of the present multipliers.
std::pair<double, double> mean_contrast(const Multipliers& x) {
    double s = 0, ss = 0, n = 0;
    for (double v : x.m)
        if (!std::isnan(v)) s += v, ss += v * v, ++n;
    const double mean = s / n;
    return {mean, std::sqrt(ss / n - mean * mean) / mean};
}

/// (integral a(x) a(x - d) dx)^2 / (integral a^2)^2 over |x| <= 12 (the pattern's applied extent).
double overlap(const std::function<double(double)>& a, double d) {
    double ab = 0, aa = 0;
    for (int i = -12 * 1024; i <= 12 * 1024; ++i) {
        const double x = i / 1024.0;
        ab += a(x) * (std::abs(x - d) <= 12 ? a(x - d) : 0.0), aa += a(x) * a(x);
    }
    return ab * ab / (aa * aa);
}

/// AF of a uniform 64-element line array (the Dirichlet kernel) as a function of x = angle / (-3 dB
/// full width of |AF|^2): sin(32 psi) / (64 sin(psi / 2)), psi = 2 psi3 x, |AF(psi3)|^2 = 1/2.
double rect_af(double x) {
    auto af = [](double psi) {
        return std::abs(psi) < 1e-12 ? 1.0 : std::sin(32 * psi) / (64 * std::sin(psi / 2));
    };
    double lo = 0, hi = 0.2; // bisection for psi3
    for (int i = 0; i < 80; ++i)
        (af(0.5 * (lo + hi)) * af(0.5 * (lo + hi)) > 0.5 ? lo : hi) = 0.5 * (lo + hi);
    return af(2 * lo * x);
}

} // namespace

TEST_CASE("speckle grain: neighbouring beams and bins share speckle as the pattern and pulse overlap",
          "[sensor][speckle][grain]") {
    SceneDesc s = grain_floor();
    s.sensor.speckle = Speckle::Rayleigh;
    s.sensor.azimuth_window = AzimuthWindow::Rect, s.sensor.beamformer = Beamformer::Lens;
    const double spacing = s.sonar.azimuth_fov_deg / s.sonar.beams;
    s.sensor.azimuth_beamwidth_deg = 2.5 * spacing; // beams 2.5x wider than their spacing, as on an Oculus
    const double dr = (s.sonar.range_max_m - s.sonar.range_min_m) / s.sonar.range_bins;
    s.sensor.range_resolution_m = 2.5 * dr, s.sensor.pulse = Pulse::Cw;
    const Multipliers m = multipliers(s, 40); // 40 beams: the rect pattern's reach beyond its main lobe
    const auto [mean, contrast] = mean_contrast(m);
    CHECK(mean == Approx(1.0).margin(0.02));
    CHECK(contrast == Approx(1.0).margin(0.05));

    const double rho_beams = overlap(rect_af, 1 / 2.5);                                               // 0.654
    const double a = 1 / 2.5, rho_range = std::pow((2.0 / 3 - a * a + a * a * a / 2) / (2.0 / 3), 2); // 0.653
    CHECK(correlation(m, 0, 1) == Approx(rho_beams).margin(0.1));
    CHECK(correlation(m, 1, 0) == Approx(rho_range).margin(0.1));
    CHECK(correlation(m, 0, 2) == Approx(overlap(rect_af, 2 / 2.5)).margin(0.1)); // 0.133
    CHECK(correlation(m, 3, 0) == Approx(0.0).margin(0.05)); // beyond the pulse: independent
}

TEST_CASE("speckle grain: a lens sonar's beams barely overlap and stay nearly independent",
          "[sensor][speckle][grain]") {
    SceneDesc s = grain_floor();
    apply_setting(s, "sonar.device", "aris3000-hf", "test");
    apply_setting(s, "sensor.model", "device", "test");
    apply_setting(s, "sensor.speckle", "rayleigh", "test");
    s.sonar.pose.position_m = {0, 0, 1}, s.sonar.pose.orientation_deg = {0, 30, 0};
    const Multipliers m = multipliers(s, 12);
    const double w = azimuth_beamwidth_deg(s), spacing = s.sonar.azimuth_fov_deg / s.sonar.beams;
    const ArrayPattern& taylor = array_pattern(s.sensor.azimuth_window, s.sensor.taylor_sidelobe_db);
    const double rho = overlap([&](double x) { return taylor.amplitude(x); }, spacing / w); // 0.236 / 0.24
    CHECK(rho < 0.2); // 0.146 with the preset's taylor -25 dB pattern
    CHECK(correlation(m, 0, 1) == Approx(rho).margin(0.1));
    CHECK(std::abs(correlation(m, 0, 2)) < 0.05); // two beams apart: independent
    // Along range the 6 mm pulse over 3.9 mm bins (a = dr / dr_res = 0.651): rho = 0.327.
    const double a =
        (s.sonar.range_max_m - s.sonar.range_min_m) / s.sonar.range_bins / s.sensor.range_resolution_m;
    CHECK(correlation(m, 1, 0) ==
          Approx(std::pow((2.0 / 3 - a * a + a * a * a / 2) / (2.0 / 3), 2)).margin(0.1));
    CHECK(mean_contrast(m).second == Approx(1.0).margin(0.05));
}

TEST_CASE("speckle grain: K speckle keeps its scintillation index through the formed field",
          "[sensor][speckle][grain]") {
    SceneDesc s = grain_floor();
    s.sensor.speckle = Speckle::K, s.sensor.speckle_k_shape = 4;
    s.sensor.azimuth_window = AzimuthWindow::Rect, s.sensor.beamformer = Beamformer::Lens;
    s.sensor.azimuth_beamwidth_deg = 2.5 * s.sonar.azimuth_fov_deg / s.sonar.beams;
    const auto [mean, contrast] = mean_contrast(multipliers(s, 40));
    CHECK(mean == Approx(1.0).margin(0.03));
    CHECK(contrast == Approx(std::sqrt(1 + 2 / 4.0)).epsilon(0.05)); // 1.225
}

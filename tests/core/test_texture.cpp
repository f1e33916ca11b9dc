// Seabed texture (shading/texture.hpp): the field's statistics against its keys (closed forms), the linear
// mean kept, the texture fixed to the world, and off by default.
#include "support.hpp"

#include "core/data/pose.hpp"
#include "core/pipeline/simulator.hpp"
#include "core/scene/sampling_scheme.hpp"
#include "core/shading/texture.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>

using namespace sonarsim;

namespace {

constexpr double kBeta = 0.23025850929940458; // ln 10 / 10

/// Samples f on an n x n grid of spacing h over the plane z = 0.3 (row-major, x fastest).
std::vector<double> sample(const std::function<double(const glm::dvec3&)>& f, int n, double h) {
    std::vector<double> v(size_t(n) * size_t(n));
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            v[size_t(j) * size_t(n) + size_t(i)] = f({i * h - 20.0, j * h + 3.0, 0.3});
    return v;
}

double mean(const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return s / double(v.size());
}

/// The lag [m] at which the autocorrelation along x (dx = 1) or y (dx = 0) falls to 1/e, interpolated.
double correlation_length_m(const std::vector<double>& v, int n, double h, bool along_x) {
    const double m = mean(v);
    auto cov = [&](int lag) {
        double s = 0;
        size_t count = 0;
        for (int j = 0; j < n - (along_x ? 0 : lag); ++j)
            for (int i = 0; i < n - (along_x ? lag : 0); ++i) {
                const size_t a = size_t(j) * size_t(n) + size_t(i);
                const size_t b = along_x ? a + size_t(lag) : a + size_t(lag) * size_t(n);
                s += (v[a] - m) * (v[b] - m), ++count;
            }
        return s / double(count);
    };
    const double c0 = cov(0);
    double prev = 1;
    for (int lag = 1; lag < n / 4; ++lag) {
        const double c = cov(lag) / c0;
        if (c < std::exp(-1.0)) return h * (lag - 1 + (prev - std::exp(-1.0)) / (prev - c));
        prev = c;
    }
    return -1;
}

Material textured(double rms_db, double correlation_m) {
    Material m;
    m.texture_rms_db = rms_db, m.texture_correlation_m = correlation_m;
    return m;
}

const glm::dmat3 kWorld(1.0);
const glm::dvec3 kOrigin(0.0);

} // namespace

TEST_CASE("texture field: unit linear mean, rms and correlation length as set", "[texture]") {
    for (double rms : {2.0, 5.0})
        for (double corr : {0.3, 2.0}) {
            INFO("rms " << rms << " dB, correlation " << corr << " m");
            const MaterialTexture t = material_texture(textured(rms, corr), kWorld, kOrigin, 7);
            const int n = 500;
            const double h = corr / 4; // 125 correlation lengths a side
            const auto level = sample([&](const glm::dvec3& p) { return t.level_db(p); }, n, h);
            // The linear mean over 1000 x 1000 points one correlation length apart (nearly independent).
            auto lin =
                sample([&](const glm::dvec3& p) { return std::exp(kBeta * t.level_db(p)); }, 1000, corr);
            CHECK(mean(lin) == Approx(1.0).epsilon(0.02)); // without the offset: exp(beta^2 rms^2 / 2)
            const double m = mean(level);
            CHECK(m == Approx(-rms * rms * kBeta / 2).margin(0.05 * rms)); // the offset itself
            std::vector<double> d2(level.size());
            for (size_t k = 0; k < level.size(); ++k) d2[k] = (level[k] - m) * (level[k] - m);
            CHECK(std::sqrt(mean(d2)) == Approx(rms).epsilon(0.15));
            CHECK(correlation_length_m(level, n, h, true) == Approx(corr).epsilon(0.15));
            CHECK(correlation_length_m(level, n, h, false) == Approx(corr).epsilon(0.15));
        }
}

TEST_CASE("texture ripples: unit linear mean (I0), rms A / sqrt 2, period the wavelength", "[texture]") {
    Material m;
    m.ripple_amplitude_db = 4, m.ripple_wavelength_m = 0.7, m.ripple_direction_deg = 30;
    const MaterialTexture t = material_texture(m, kWorld, kOrigin, 3);
    const auto level = sample([&](const glm::dvec3& p) { return t.level_db(p); }, 300, 0.0513);
    std::vector<double> lin(level.size()), d2(level.size());
    const double mu = mean(level);
    for (size_t k = 0; k < level.size(); ++k)
        lin[k] = std::exp(kBeta * level[k]), d2[k] = (level[k] - mu) * (level[k] - mu);
    CHECK(mean(lin) == Approx(1.0).epsilon(0.02)); // without the offset: I0(4 beta) = 1.22
    CHECK(std::sqrt(mean(d2)) == Approx(4 / std::sqrt(2.0)).epsilon(0.02));
    const glm::dvec3 p(1.3, -2.1, 0), along(std::cos(deg2rad(30)), std::sin(deg2rad(30)), 0);
    CHECK(t.level_db(p + 0.7 * along) == Approx(t.level_db(p)).margin(1e-9));
    CHECK(std::abs(t.level_db(p + 0.35 * along) - t.level_db(p)) > 1e-3); // half a period differs
    CHECK(t.level_db(p + 5.0 * glm::dvec3(-along.y, along.x, 0)) == Approx(t.level_db(p)).margin(1e-9));
}

TEST_CASE("texture slope: the facet tilt has the rms and correlation length set", "[texture]") {
    Material m;
    m.slope_rms_deg = 8, m.texture_correlation_m = 0.5;
    const MaterialTexture t = material_texture(m, kWorld, kOrigin, 11);
    REQUIRE(t.slope_on);
    REQUIRE_FALSE(t.level_on);
    const double theta = deg2rad(50);
    const auto tilt = sample(
        [&](const glm::dvec3& p) { return rad2deg(std::acos(t.facet_cos(p, std::cos(theta))) - theta); }, 400,
        0.125);
    std::vector<double> d2(tilt.size());
    for (size_t k = 0; k < tilt.size(); ++k) d2[k] = tilt[k] * tilt[k];
    CHECK(std::abs(mean(tilt)) < 0.5);
    CHECK(std::sqrt(mean(d2)) == Approx(8.0).epsilon(0.15));
    CHECK(correlation_length_m(tilt, 400, 0.125, true) == Approx(0.5).epsilon(0.15));
    // The level's field is another, independent one (one lattice walk gives both).
    m.texture_rms_db = 3;
    const MaterialTexture both = material_texture(m, kWorld, kOrigin, 11);
    const auto level = sample([&](const glm::dvec3& p) { return both.at(p).level_db; }, 400, 0.125);
    const auto tilt2 = sample([&](const glm::dvec3& p) { return both.at(p).tilt_rad; }, 400, 0.125);
    const double ml = mean(level), mt = mean(tilt2);
    double sxy = 0, sxx = 0, syy = 0;
    for (size_t k = 0; k < level.size(); ++k) {
        const double a = level[k] - ml, b = tilt2[k] - mt;
        sxy += a * b, sxx += a * a, syy += b * b;
    }
    CHECK(std::abs(sxy / std::sqrt(sxx * syy)) < 0.05);
}

TEST_CASE("texture moves with its object and not with the sonar", "[texture]") {
    Material m = textured(4, 0.4);
    m.ripple_amplitude_db = 2;
    const glm::dmat3 R = rotation_matrix({10, -20, 35});
    const glm::dvec3 t(3, -1, 2), local(0.4, 0.7, -0.2);
    const MaterialTexture a = material_texture(m, kWorld, kOrigin, 5), b = material_texture(m, R, t, 5);
    CHECK(b.level_db(R * local + t) == Approx(a.level_db(local)).margin(1e-9));
    CHECK(std::abs(b.level_db(local) - a.level_db(local)) > 1e-3);
}

namespace {

/// A flat floor seen from 1 m above with the sonar level (pitch 0), so that a yaw of one beam spacing moves
/// every beam onto its neighbour's rays.
SceneDesc level_floor_scene(double yaw_deg) {
    SceneDesc s;
    s.objects.clear();
    s.seafloor = Seafloor{};
    s.sonar.pose.position_m = {0, 0, 1};
    s.sonar.pose.orientation_deg = {0, 0, yaw_deg};
    s.sonar.beams = 64, s.sonar.azimuth_fov_deg = 32, s.sonar.elevation_fov_deg = 40;
    s.sonar.range_min_m = 2.5, s.sonar.range_max_m = 8, s.sonar.range_bins = 200;
    set_scheme(s.sampling, SamplingScheme::Spread);
    return s;
}

PolarImage render_ideal(const SceneDesc& s) {
    Simulator sim(s);
    return sim.render()->ideal();
}

} // namespace

TEST_CASE("a world point keeps its texture when the sonar turns", "[texture]") {
    const double spacing = 32.0 / 64;
    SceneDesc a = level_floor_scene(0), b = level_floor_scene(spacing);
    a.seafloor->material = b.seafloor->material = textured(5, 0.15);
    const PolarImage ia = render_ideal(a), ib = render_ideal(b);
    // b's beam i looks where a's beam i - 1 looks (beam 0 is the port edge, at the largest azimuth).
    double worst_shifted = 0, sum_same = 0;
    size_t count = 0;
    for (int k = 0; k < ia.bins; ++k)
        for (int i = 1; i < ia.beams; ++i) {
            const float x = ib.at(k, i), y = ia.at(k, i - 1), z = ia.at(k, i);
            if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) continue;
            worst_shifted = std::max(worst_shifted, double(std::abs(x - y)));
            sum_same += std::abs(x - z), ++count;
        }
    REQUIRE(count > 5000);
    CHECK(worst_shifted < 0.01);           // the same world points, the same texture
    CHECK(sum_same / double(count) > 1.0); // the texture is there: neighbouring beams differ
}

TEST_CASE("a textured floor keeps the mean level, and rms 0 changes nothing", "[texture]") {
    SceneDesc s = level_floor_scene(0);
    s.sonar.pose.position_m = {0, 0, 2};
    s.sonar.pose.orientation_deg = {0, 15, 0};
    s.sonar.beams = 256, s.sonar.azimuth_fov_deg = 90, s.sonar.range_max_m = 40, s.sonar.range_bins = 400;
    s.sampling.elevation_rays = 400, s.sampling.azimuth_rays = 2;
    const PolarImage off = render_ideal(s);
    SceneDesc t = s;
    t.seafloor->material.texture_correlation_m = 0.1, t.seafloor->material.ripple_wavelength_m = 0.3;
    const PolarImage zero = render_ideal(t);
    CHECK(zero.level_db == off.level_db); // rms 0, ripples 0, slope 0: off
    t.seafloor->material.texture_rms_db = 4;
    const PolarImage on = render_ideal(t);
    double ratio = 0, spread = 0;
    size_t count = 0;
    for (size_t n = 0; n < off.level_db.size(); ++n)
        if (std::isfinite(off.level_db[n])) {
            const double d = double(on.level_db[n]) - double(off.level_db[n]);
            ratio += std::exp(kBeta * d), spread += std::abs(d), ++count;
        }
    REQUIRE(count > 50000);
    CHECK(ratio / double(count) == Approx(1.0).epsilon(0.02));
    CHECK(spread / double(count) > 0.5); // and it is visible
}

// The sensor stage against closed forms: receive beam pattern, elevation pattern, range response, speckle
// statistics, noise power, TVG, determinism and world anchoring. Synthetic images test each effect alone;
// rendered ones test them in the pipeline.
#include "support.hpp"

#include "core/io/output.hpp"
#include "core/scene/params.hpp"
#include "core/data/pose.hpp"
#include "core/analysis/reference.hpp"
#include "core/scene/scene_io.hpp"
#include "core/base/fast_math.hpp"
#include "core/sensor/keyed_variates.hpp"
#include "core/sensor/sensor.hpp"
#include "core/grid/sensor_patterns.hpp"
#include "core/shading/accumulate.hpp"
#include "core/grid/sonar_grid.hpp"
#include "core/pipeline/simulator.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <numeric>

using namespace sonarsim;

namespace {

constexpr float kNoEcho = -std::numeric_limits<float>::infinity();

/// A scene whose sensor settings the tests set themselves (ideal sensor, no floor, no objects).
SceneDesc bare_scene(int beams, int bins) {
    SceneDesc s = default_scene();
    s.objects.clear();
    s.seafloor.reset();
    s.sonar.beams = beams, s.sonar.range_bins = bins;
    return s;
}

PolarImage image_of(const SceneDesc& s, float fill) {
    PolarImage img;
    img.bins = s.sonar.range_bins, img.beams = s.sonar.beams;
    img.level_db.assign(size_t(img.bins) * img.beams, fill);
    return img;
}

/// The -3 dB full width of a sampled peak (linear interpolation between samples), in samples.
double half_power_width(const std::vector<double>& v, size_t peak) {
    auto cross = [&](int dir) {
        size_t i = peak;
        while (v[size_t(int(i) + dir)] > 0.5 * v[peak]) i = size_t(int(i) + dir);
        const double a = v[i], b = v[size_t(int(i) + dir)];
        return double(i) + dir * (a - 0.5 * v[peak]) / (a - b);
    };
    return cross(+1) - cross(-1);
}

} // namespace

TEST_CASE("the rect array pattern has its first sidelobe at -13.3 dB and the width it is given", "[sensor]") {
    const ArrayPattern rect(AzimuthWindow::Rect, -30);
    CHECK(rect(0.5) == Approx(0.5).margin(1e-6));
    CHECK(rect.first_sidelobe_db() == Approx(-13.26).margin(0.1));
    const ArrayPattern hann(AzimuthWindow::Hann, -30);
    CHECK(hann(0.5) == Approx(0.5).margin(1e-6));
    CHECK(hann.first_sidelobe_db() == Approx(-31.5).margin(0.5)); // Harris 1978, Table 1
    const ArrayPattern taylor(AzimuthWindow::Taylor, -35);
    CHECK(taylor.first_sidelobe_db() == Approx(-35).margin(1.0));
}

TEST_CASE("a point target's response across finely spaced beams follows the array factor", "[sensor]") {
    // 512 beams over 32 deg (0.0625 deg apart), a 1 deg receive beam: 16 beams per -3 dB width.
    SceneDesc s = bare_scene(512, 64);
    s.sonar.azimuth_fov_deg = 32;
    s.sensor.azimuth_window = AzimuthWindow::Rect;
    s.sensor.azimuth_beamwidth_deg = 1.0;
    REQUIRE(azimuth_subcolumns(s) == 1);
    PolarImage ideal = image_of(s, kNoEcho);
    const int target = 200, bin = 30;
    ideal.level_db[size_t(bin) * 512 + target] = 60.0f;
    const PolarImage out = apply_sensor(ideal, nullptr, s, 0.0);
    std::vector<double> across(512);
    for (int b = 0; b < 512; ++b) across[size_t(b)] = test::lin(out.at(bin, b));
    CHECK(10 * std::log10(across[target]) == Approx(60.0).margin(1e-4)); // peak gain 1
    CHECK(half_power_width(across, target) * 32.0 / 512 == Approx(1.0).margin(0.0625 / 2));
    // First sidelobe: the largest value beyond the first null on either side.
    size_t i = target;
    while (across[i + 1] < across[i]) ++i;
    double side = 0;
    for (size_t j = i; j < i + 40; ++j) side = std::max(side, across[j]);
    CHECK(10 * std::log10(side / across[target]) == Approx(-13.3).margin(1.0));
    // Nothing leaks to other range bins, and beams beyond the pattern's reach stay empty.
    CHECK(out.at(bin + 1, target) == kNoEcho);
    CHECK(out.at(bin, 0) == kNoEcho);
}

TEST_CASE("an array beamformer widens its beams as 1 over cos of the steering angle", "[sensor]") {
    SceneDesc s = bare_scene(512, 8);
    s.sonar.azimuth_fov_deg = 120;
    s.sensor.azimuth_window = AzimuthWindow::Hann;
    s.sensor.azimuth_beamwidth_deg = 2.0;
    s.sensor.beamformer = Beamformer::Array;
    PolarImage ideal = image_of(s, kNoEcho);
    const int centre = 256, edge = 40; // beam 40 is at 60 - 40.5 * 120 / 512 = 50.5 deg
    ideal.level_db[size_t(4) * 512 + centre] = 50.0f;
    ideal.level_db[size_t(4) * 512 + edge] = 50.0f;
    const PolarImage out = apply_sensor(ideal, nullptr, s, 0.0);
    std::vector<double> across(512);
    for (int b = 0; b < 512; ++b) across[size_t(b)] = test::lin(out.at(4, b));
    const double spacing = 120.0 / 512, a_edge = 60 - (edge + 0.5) * spacing;
    // The response seen across beams is the pattern of each output beam sampled at the target: close to the
    // beam's own width at the edge (the width changes little over a few beams).
    CHECK(half_power_width(across, centre) * spacing ==
          Approx(2.0 / std::cos(deg2rad(60 - 256.5 * spacing))).epsilon(0.05));
    CHECK(half_power_width(across, edge) * spacing == Approx(2.0 / std::cos(deg2rad(a_edge))).epsilon(0.05));
}

TEST_CASE("the shared receive pattern is made once per geometry and pattern and equals a fresh one",
          "[sensor]") {
    SceneDesc s = bare_scene(256, 8);
    s.sensor.azimuth_window = AzimuthWindow::Taylor;
    s.sensor.azimuth_beamwidth_deg = 1.0;
    s.sensor.beamformer = Beamformer::Array;
    const auto shared = shared_azimuth_beamforming(s, true);
    CHECK(shared_azimuth_beamforming(s, true) == shared); // kept for the next frame
    const AzimuthBeamforming fresh = make_azimuth_beamforming(s, true);
    CHECK(shared->first == fresh.first);
    CHECK(shared->count == fresh.count);
    CHECK(shared->offset == fresh.offset);
    CHECK(shared->weight == fresh.weight);
    CHECK(shared->amplitude == fresh.amplitude);
    CHECK(shared_azimuth_beamforming(s, false)->amplitude.empty()); // without amplitudes: its own entry
    // Any key changed: another pattern.
    for (int change = 0; change < 5; ++change) {
        SceneDesc t = s;
        if (change == 0) t.sensor.azimuth_window = AzimuthWindow::Hann;
        if (change == 1) t.sensor.taylor_sidelobe_db = -40;
        if (change == 2) t.sensor.azimuth_beamwidth_deg = 1.5;
        if (change == 3) t.sensor.beamformer = Beamformer::Lens;
        if (change == 4) t.sonar.azimuth_fov_deg = s.sonar.azimuth_fov_deg / 2;
        const auto other = shared_azimuth_beamforming(t, true);
        CHECK(other != shared);
        CHECK(other->weight == make_azimuth_beamforming(t, true).weight);
    }
}

TEST_CASE("the elevation patterns have their -3 dB width and the traced span they promise", "[sensor]") {
    SceneDesc s = default_scene();
    s.sensor.elevation_beamwidth_deg = 10;
    for (auto kind : {ElevationPattern::Gaussian, ElevationPattern::Sinc}) {
        s.sensor.elevation_pattern = kind;
        const ElevationWeight w(s);
        CHECK(w(0) == Approx(1.0));
        CHECK(w(deg2rad(5)) == Approx(0.5).margin(1e-4));
        CHECK(w(-deg2rad(5)) == Approx(0.5).margin(1e-4));
        const double edge = w(w.traced_fov_rad() / 2);
        if (kind == ElevationPattern::Gaussian) CHECK(10 * std::log10(edge) == Approx(-30).margin(0.05));
        if (kind == ElevationPattern::Sinc) CHECK(edge < 1e-6); // the second null
    }
    s.sensor.elevation_pattern = ElevationPattern::Flat;
    CHECK(ElevationWeight(s).traced_fov_rad() == Approx(deg2rad(s.sonar.elevation_fov_deg)));
}

TEST_CASE("a flat floor seen through a gaussian elevation pattern matches the weighted floor integral",
          "[sensor][accuracy]") {
    SceneDesc s = default_scene();
    s.objects.clear();
    s.sensor.elevation_pattern = ElevationPattern::Gaussian;
    Simulator sim(s);
    const auto f = sim.render();
    const PolarImage ref = floor_reference(s, 4);
    const double err = test::relative_l1(test::echo_intensity(f->ideal(), s.sonar.noise_level_db),
                                         test::echo_intensity(ref, s.sonar.noise_level_db));
    CHECK(err < 0.01);
    // The pattern reaches beyond the 14 deg aperture: more of the floor echoes than with the hard cut.
    SceneDesc hard = s;
    hard.sensor.elevation_pattern = ElevationPattern::Flat;
    const auto g = Simulator(hard).render();
    auto echoing = [](const PolarImage& img) {
        return std::count_if(img.level_db.begin(), img.level_db.end(),
                             [](float v) { return std::isfinite(v); });
    };
    CHECK(echoing(f->ideal()) > echoing(g->ideal()));
}

TEST_CASE("the range response keeps the energy and has the kernel's shape", "[sensor]") {
    const double dr = 0.01;
    for (Pulse pulse : {Pulse::Cw, Pulse::Chirp}) {
        const double res = 0.1; // ten bins
        const std::vector<double> h = range_kernel(pulse, res, dr);
        CHECK(std::accumulate(h.begin(), h.end(), 0.0) == Approx(1.0).margin(1e-12));
        const int half = int(h.size() / 2);
        if (pulse == Pulse::Cw) {    // integral of (1 - |x|/res)^2 over each bin, normalised: closed form
            auto F = [&](double x) { // antiderivative of (1 - x/res)^2 for 0 <= x <= res
                const double u = std::min(x, res) / res;
                return res * (1 - std::pow(1 - u, 3)) / 3;
            };
            const double total = 2 * F(res);
            for (int t = 0; t <= half; ++t) {
                const double a = std::max(0.0, (t - 0.5) * dr), b = (t + 0.5) * dr;
                const double expect = t == 0 ? 2 * F(0.5 * dr) / total : (F(b) - F(a)) / total;
                CHECK(h[size_t(half + t)] == Approx(expect).margin(2e-5));
                CHECK(h[size_t(half - t)] == Approx(h[size_t(half + t)]));
            }
        } else { // sinc^2: zero near every multiple of the resolution, symmetric
            CHECK(h[size_t(half + 10)] < 1e-3 * h[size_t(half)]);
            CHECK(h[size_t(half + 15)] > 10 * h[size_t(half + 10)]); // the first sidelobe
        }
        // Applied to an impulse: the output is the kernel, and the energy is kept.
        SceneDesc s = bare_scene(4, 400);
        s.sonar.range_min_m = 1, s.sonar.range_max_m = 1 + 400 * dr;
        s.sensor.range_resolution_m = res, s.sensor.pulse = pulse;
        PolarImage ideal = image_of(s, kNoEcho);
        ideal.level_db[size_t(200) * 4 + 1] = 30.0f;
        const PolarImage out = apply_sensor(ideal, nullptr, s, 0.0);
        double energy = 0;
        for (int k = 0; k < 400; ++k) energy += test::lin(out.at(k, 1));
        CHECK(energy == Approx(1000.0).epsilon(1e-6));
        for (int t = -half; t <= half; ++t)
            CHECK(test::lin(out.at(200 + t, 1)) ==
                  Approx(1000.0 * h[size_t(t + half)]).epsilon(1e-5).margin(1e-9));
    }
}

namespace {

/// Speckle multipliers of a floor image: the sensor's output over the ideal image, per echoing cell.
std::vector<double> speckle_multipliers(const SceneDesc& s) {
    Simulator sim(s);
    const auto f = sim.render();
    std::vector<double> m;
    for (size_t i = 0; i < f->polar().level_db.size(); ++i)
        if (std::isfinite(f->ideal().level_db[i]))
            m.push_back(std::pow(10.0, (double(f->polar().level_db[i]) - f->ideal().level_db[i]) / 10));
    return m;
}

SceneDesc speckled_floor(Speckle kind) {
    SceneDesc s = default_scene();
    s.objects.clear();
    s.sonar.beams = 256, s.sonar.range_bins = 1024;
    s.sensor.speckle = kind;
    return s;
}

} // namespace

TEST_CASE("speckle on a floor is exponential with contrast 1", "[sensor][speckle]") {
    std::vector<double> m = speckle_multipliers(speckled_floor(Speckle::Rayleigh));
    REQUIRE(m.size() > 40000);
    const double n = double(m.size());
    const double mean = std::accumulate(m.begin(), m.end(), 0.0) / n;
    double var = 0;
    for (double x : m) var += (x - mean) * (x - mean);
    const double contrast = std::sqrt(var / n) / mean;
    CHECK(mean == Approx(1.0).margin(0.02));
    CHECK(contrast == Approx(1.0).margin(0.05));
    // Kolmogorov-Smirnov against Exp(1): D below the 1 % critical value 1.63 / sqrt(n).
    std::sort(m.begin(), m.end());
    double D = 0;
    for (size_t i = 0; i < m.size(); ++i) {
        const double F = 1 - std::exp(-m[i]);
        D = std::max({D, std::abs(F - double(i) / n), std::abs(F - double(i + 1) / n)});
    }
    CHECK(D < 1.63 / std::sqrt(n));
}

TEST_CASE("K-distributed speckle has the scintillation index of its shape", "[sensor][speckle]") {
    SceneDesc s = speckled_floor(Speckle::K);
    s.sensor.speckle_k_shape = 4;
    const std::vector<double> m = speckle_multipliers(s);
    const double n = double(m.size());
    double m1 = 0, m2 = 0;
    for (double x : m) m1 += x, m2 += x * x;
    m1 /= n, m2 /= n;
    const double si = m2 / (m1 * m1) - 1; // 1 + 2 / alpha
    CHECK(m1 == Approx(1.0).margin(0.03));
    CHECK(2 / (si - 1) == Approx(4.0).epsilon(0.12));
}

TEST_CASE("a noise-only image has the mean power of the noise level", "[sensor]") {
    SceneDesc s = bare_scene(128, 512);
    s.sensor.noise = true;
    const auto f = Simulator(s).render();
    double mean = 0;
    for (float v : f->polar().level_db) {
        REQUIRE(std::isfinite(v));
        mean += test::lin(v);
    }
    mean /= double(f->polar().level_db.size());
    CHECK(mean == Approx(1.0).margin(0.015)); // L_EN 0 dB: the noise level; 65536 cells, 0.4 % std
    // The ideal sensor keeps -inf in empty water.
    s.sensor.noise = false;
    const auto g = Simulator(s).render();
    CHECK(std::all_of(g->polar().level_db.begin(), g->polar().level_db.end(),
                      [](float v) { return v == kNoEcho; }));
}

TEST_CASE("TVG compensates N log R plus absorption exactly", "[sensor]") {
    SceneDesc s = bare_scene(2, 300);
    s.sonar.range_min_m = 1, s.sonar.range_max_m = 61;
    const double alpha = 0.3;
    for (auto [law, n] : {std::pair{Tvg::Log20, 20}, std::pair{Tvg::Log40, 40}}) {
        s.sensor.tvg = law;
        s.sensor.gain_db = 6;
        PolarImage ideal = image_of(s, kNoEcho);
        for (int k = 0; k < 300; ++k) {
            const double r = 1 + (k + 0.5) * 0.2;
            ideal.level_db[size_t(k) * 2] = float(150 - n * std::log10(r) - 2 * alpha * r);
        }
        const PolarImage out = apply_sensor(ideal, nullptr, s, alpha);
        for (int k = 0; k < 300; ++k) CHECK(out.at(k, 0) == Approx(156.0).margin(2e-4));
    }
}

TEST_CASE("speckle and noise are deterministic and anchored to the world", "[sensor][speckle]") {
    SceneDesc s = default_scene();
    apply_setting(s, "sensor.model", "device", "test");
    auto npy = [](const SceneDesc& sc) { return encode_npy(Simulator(sc).render()->polar()); };
    const auto a = npy(s);
    CHECK(npy(s) == a); // same seed, same pose: the same bytes
    SceneDesc other = s;
    other.sensor.seed = 2;
    CHECK(npy(other) != a);

    // Speckle alone: moving the sonar 3 cm sideways decorrelates the multipliers pixel by pixel.
    SceneDesc sp = speckled_floor(Speckle::Rayleigh);
    SceneDesc moved = sp;
    moved.sonar.pose.position_m[1] += 0.03;
    auto log_multipliers = [](const SceneDesc& sc) {
        const auto f = Simulator(sc).render();
        std::vector<double> v(f->polar().level_db.size(), std::nan(""));
        for (size_t i = 0; i < v.size(); ++i)
            if (std::isfinite(f->ideal().level_db[i]))
                v[i] = double(f->polar().level_db[i]) - f->ideal().level_db[i];
        return v;
    };
    const std::vector<double> x = log_multipliers(sp), y = log_multipliers(moved), z = log_multipliers(sp);
    auto correlation = [](const std::vector<double>& p, const std::vector<double>& q) {
        double sp = 0, sq = 0, spp = 0, sqq = 0, spq = 0, n = 0;
        for (size_t i = 0; i < p.size(); ++i)
            if (!std::isnan(p[i]) && !std::isnan(q[i]))
                sp += p[i], sq += q[i], spp += p[i] * p[i], sqq += q[i] * q[i], spq += p[i] * q[i], ++n;
        const double cov = spq / n - sp / n * sq / n;
        return cov / std::sqrt((spp / n - sp / n * sp / n) * (sqq / n - sq / n * sq / n));
    };
    CHECK(correlation(x, z) == Approx(1.0));
    CHECK(std::abs(correlation(x, y)) < 0.1);
}

TEST_CASE("the device model turns every effect on and the ideal model every effect off", "[sensor]") {
    SceneDesc s = default_scene();
    apply_setting(s, "sensor.model", "device", "test");
    CHECK_FALSE(sensor_is_ideal(s));
    CHECK(s.sensor.speckle == Speckle::Rayleigh);
    CHECK(s.sensor.noise);
    CHECK(s.display.auto_range);
    apply_setting(s, "sensor.model", "ideal", "test");
    CHECK(sensor_is_ideal(s));
    CHECK(s.sensor.elevation_pattern == ElevationPattern::Flat);
    // Keys given in a scene file override what the model turns on.
    const SceneDesc f = parse_scene(R"({"sensor": {"model": "device", "speckle": "off"}})", "t.json", ".");
    CHECK(f.sensor.speckle == Speckle::Off);
    CHECK(f.sensor.noise);
    // ... also when --set chooses the model.
    const SceneDesc g =
        parse_scene(R"({"sensor": {"noise": false}})", "t.json", ".", {{"sensor.model", "device"}});
    CHECK_FALSE(g.sensor.noise);
    CHECK(g.sensor.speckle == Speckle::Rayleigh);
}

TEST_CASE("each effect of the sensor stage alone makes the sensor non-ideal", "[sensor]") {
    const SceneDesc ideal = default_scene();
    REQUIRE(sensor_is_ideal(ideal));
    const std::vector<std::pair<const char*, json>> effects = {
        {"sensor.azimuth_window", "hann"}, {"sensor.range_resolution_m", 0.01},
        {"sensor.speckle", "k"},           {"sensor.noise", true},
        {"sensor.tvg", "20log"},           {"sensor.gain_db", -3.0}};
    for (const auto& [key, value] : effects) {
        INFO(key);
        SceneDesc s = ideal;
        apply_setting(s, key, value, "test");
        CHECK_FALSE(sensor_is_ideal(s));
    }
    // Not effects of the sensor stage: the elevation pattern (the trace's), the shape of an effect that is
    // off.
    for (const auto& [key, value] :
         std::vector<std::pair<const char*, json>>{{"sensor.elevation_pattern", "sinc"},
                                                   {"sensor.taylor_sidelobe_db", -40.0},
                                                   {"sensor.pulse", "chirp"},
                                                   {"sensor.seed", 9}}) {
        INFO(key);
        SceneDesc s = ideal;
        apply_setting(s, key, value, "test");
        CHECK(sensor_is_ideal(s));
    }
}

TEST_CASE("the automatic display range spans the fan's 5th to 99.5th percentile", "[sensor][display]") {
    // One beam, 1001 bins over 100 ... 101 m (range weights within 1 % of each other): levels 0 ... 39.96 dB.
    SonarParams sonar;
    sonar.range_min_m = 100, sonar.range_max_m = 101, sonar.beams = 1, sonar.range_bins = 1001;
    PolarImage img;
    img.bins = 1001, img.beams = 1;
    for (int i = 0; i < 1000; ++i) img.level_db.push_back(float(i) / 25);
    img.level_db.push_back(kNoEcho); // not counted
    DisplayParams d;
    d.auto_range = true;
    const DisplayParams e = effective_display(img, d, sonar);
    CHECK(e.lo_db == Approx(2.0).margin(0.08)); // within 2 samples of the exact quantiles
    CHECK(e.hi_db == Approx(39.8).margin(0.08));
    // Samples count as the fan's area does, in proportion to their range: over 0 ... 1 m the area below
    // range x grows as x^2, so the 5th percentile lies at sqrt(0.05) of the range.
    sonar.range_min_m = 0, sonar.range_max_m = 1;
    CHECK(effective_display(img, d, sonar).lo_db == Approx(40 * std::sqrt(0.05)).margin(0.1));
    // A wider image: black at most kAutoDisplaySpanDb below white.
    for (float& v : img.level_db) v *= 4;
    const DisplayParams w = effective_display(img, d, sonar);
    CHECK(w.hi_db - w.lo_db == Approx(kAutoDisplaySpanDb));
    d.auto_range = false;
    CHECK(effective_display(img, d, sonar).lo_db == d.lo_db);
}

TEST_CASE("the sensor's fast elementary functions keep their stated error bounds", "[sensor][fast]") {
    double worst_exp = 0, worst_log = 0;
    for (int i = 0; i <= 200000; ++i) {
        const double x = -1000.0 * i / 200000 - 1e-3 * (i % 7); // 0 ... -1000, dense and irregular
        worst_exp = std::max(worst_exp, std::abs(fast::exp2_nonpositive(x) / std::exp2(x) - 1));
        const double y = std::exp2(-600.0 * i / 200000) * (1 + 0.37 * (i % 11) / 11); // 1e-180 ... 1.4
        worst_log = std::max(worst_log, std::abs(fast::log2_positive(y) - std::log2(y)));
    }
    CHECK(worst_exp < 1e-15);
    CHECK(worst_log < 2e-13); // one ulp of results near -512
    CHECK(fast::exp2_nonpositive(-1023) == 0.0);
    CHECK(fast::exp2_nonpositive(-1022) == std::exp2(-1022.0));
    CHECK(fast::exp2_nonpositive(std::nan("")) == 0.0);
    CHECK(fast::log2_positive(1e-310) == Approx(std::log2(1e-310))); // denormal
}

TEST_CASE("the single-precision lane functions keep their stated error bounds", "[sensor][fast]") {
    double worst_ln = 0, worst_cos = 0, worst_sin = 0;
    for (int i = 0; i <= 200000; ++i) {
        // The uniforms the variates use: (m + 1/2) 2^-24, here spread from 2^-25 to 1 in log and in value.
        const float u = i % 2 ? float(std::exp2(-25.0 * i / 200000)) : float(i) / 200000 + 0x1.0p-25f;
        const double ln = std::log(double(u)); // relative to |ln u| where that exceeds 1
        worst_ln = std::max(worst_ln, std::abs(double(fast::ln_f(u)) - ln) / std::max(1.0, std::abs(ln)));
        const float t = float(i) / 200000 - 0.5f;
        float c, s;
        fast::sincos_turn_f(t, c, s);
        worst_cos = std::max(worst_cos, std::abs(double(c) - std::cos(2 * kPi * double(t))));
        worst_sin = std::max(worst_sin, std::abs(double(s) - std::sin(2 * kPi * double(t))));
    }
    CHECK(worst_ln < 1.2e-7);
    CHECK(worst_cos < 3e-7);
    CHECK(worst_sin < 3e-7);
    CHECK(worst_ln > 0); // single precision: not exact
}

TEST_CASE("the output levels' logarithm keeps its error bound over the whole double range",
          "[sensor][fast]") {
    double worst = 0;
    for (int i = 0; i <= 200000; ++i) {
        const double x =
            std::exp2(-1070.0 * i / 200000 + 20) * (1 + 0.37 * (i % 11) / 11); // 2^20 ... 2^-1050
        worst = std::max(worst, std::abs(fast::db_level(x) - 10 * std::log10(x)));
    }
    CHECK(worst < 1e-6);
    CHECK(fast::db_level(1e-310) == Approx(-3100.0).margin(1e-6)); // denormal
}

TEST_CASE("the single-precision 2^x keeps its error bound down to -126 and is 0 below", "[sensor][fast]") {
    double worst = 0;
    for (int i = 0; i <= 200000; ++i) {
        const float x = -126.0f * float(i) / 200000 - 1e-4f * float(i % 7); // 0 ... -126, dense and irregular
        if (x < -126.0f) continue;
        worst = std::max(worst, std::abs(double(fast::exp2_nonpositive_f(x)) / std::exp2(double(x)) - 1));
    }
    CHECK(worst < 3e-7);
    CHECK(worst > 0);
    CHECK(fast::exp2_nonpositive_f(-126.5f) == 0.0f);
    CHECK(fast::exp2_nonpositive_f(-std::numeric_limits<float>::infinity()) == 0.0f);
    CHECK(fast::exp2_nonpositive_f(std::nanf("")) == 0.0f);
    CHECK(fast::exp2_nonpositive_f(0.0f) == 1.0f);
}

TEST_CASE("the K texture's gamma draws have the mean and variance of their shape", "[sensor][speckle]") {
    for (const double shape : {0.3, 1.0, 4.0, 50.0}) {
        // 2^20 draws: mean 1 and variance 1 / shape within 4.5 standard errors.
        const int n = 1 << 20;
        std::vector<std::uint32_t> key(static_cast<size_t>(n));
        for (int i = 0; i < n; ++i) key[size_t(i)] = keyed::mix32(std::uint32_t(i) * 2654435761U);
        std::vector<double> g(static_cast<size_t>(n));
        keyed::gamma_unit_mean(n, key.data(), shape, g.data());
        double m1 = 0, m2 = 0;
        for (double v : g) m1 += v, m2 += v * v;
        m1 /= n, m2 /= n;
        const double var = m2 - m1 * m1, sd_mean = std::sqrt(1 / shape / n);
        const double sd_var = std::sqrt((2 + 6 / shape) / n) / shape; // the gamma's kurtosis: 3 + 6 / shape
        CAPTURE(shape, m1, var);
        CHECK(std::abs(m1 - 1) < 4.5 * sd_mean);
        CHECK(std::abs(var - 1 / shape) < 4.5 * sd_var);
    }
}

TEST_CASE("a cell over several receive sub-columns puts each one's echo in its own part of the footprint",
          "[sensor]") {
    // One cell as wide as its beam, on a plane whose range runs from 4.6 m at the beam's lower (starboard)
    // azimuth edge to 5.4 m at its upper, with no extent in elevation. The receive pattern cuts the beam into
    // four sub-columns (the port-most first): each sees the quarter of that range its azimuths cover, so
    // their echoes are centred at 5.3, 5.1, 4.9 and 4.7 m. Spread over the whole footprint, every one was
    // centred at 5.0 m, smearing the beam-formed image's edges.
    SceneDesc s;
    s.sonar.beams = 4, s.sonar.azimuth_fov_deg = 8;
    s.sonar.range_min_m = 4, s.sonar.range_max_m = 6, s.sonar.range_bins = 200;
    s.sensor.azimuth_window = AzimuthWindow::Hann, s.sensor.azimuth_beamwidth_deg = 2;
    REQUIRE(azimuth_subcolumns(s) == 4);
    const auto grid = sonar_grid(s.sonar);
    const int beam = 1;
    Cell c{};
    c.point_m = glm::vec3(5, 0, 0);
    c.range_m = 5, c.cos_incidence = 0.5f, c.solid_angle_sr = 1e-4f;
    c.range_e_lo_m = c.range_e_hi_m = 5;
    c.range_a_lo_m = 4.6f, c.range_a_hi_m = 5.4f;
    c.azimuth_width_rad = float(grid->beam_width_rad(beam));
    c.azimuth_rad = float(grid->beam_port_edge_rad(beam) - 0.5 * grid->beam_width_rad(beam));
    c.elevation_rad = 0, c.elevation_width_rad = 0.01f;
    c.material = kFloorMaterial;
    TraceResult hits;
    hits.beams = s.sonar.beams;
    hits.cells.resize(size_t(s.sonar.beams));
    hits.cells[size_t(beam)].push_back(c);
    Channels ch;
    ch.image = ch.sensor_inputs = true;
    const Accumulation acc = accumulate(hits, s, ch);
    REQUIRE(acc.inputs);
    const PolarImage& fine = acc.inputs->fine;
    REQUIRE(fine.beams == s.sonar.beams * 4);
    for (int q = 0; q < 4; ++q) {
        double m = 0, w = 0;
        for (int b = 0; b < fine.bins; ++b) {
            const double e = test::lin(fine.at(b, beam * 4 + q));
            m += e * grid->bin_centre_m(b), w += e;
        }
        REQUIRE(w > 0);
        INFO("sub-column " << q);
        CHECK(m / w == Approx(5.3 - 0.2 * q).margin(0.006));
    }
}

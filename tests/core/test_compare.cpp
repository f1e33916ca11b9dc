// `sonarsim compare`'s statistics on synthetic images whose values are known in closed form: fully developed
// speckle (exponential intensity), K-distributed speckle, a known range profile, a known correlation along
// range, and pairs (the same image, the image with a gain, independent realisations, a constant image).
#include "core/analysis/compare.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <complex>
#include <random>

using namespace sonarsim;

namespace {

constexpr int kBins = 400, kBeams = 200;

/// An image of intensities mean(k) x Exp(1) (x a Gamma(alpha)/alpha texture when alpha > 0), as dB.
PolarImage speckle(std::uint64_t seed, double (*mean)(int k) = nullptr, double alpha = 0) {
    std::mt19937_64 rng(seed);
    std::exponential_distribution<double> ex(1.0);
    std::gamma_distribution<double> ga(alpha > 0 ? alpha : 1.0, 1.0);
    PolarImage img;
    img.bins = kBins, img.beams = kBeams;
    for (int k = 0; k < kBins; ++k)
        for (int b = 0; b < kBeams; ++b) {
            double I = ex(rng) * (mean ? mean(k) : 1.0);
            if (alpha > 0) I *= ga(rng) / alpha;
            img.level_db.push_back(float(10 * std::log10(I) + 60));
        }
    return img;
}

double falling(int k) { // 30 dB over the window
    return std::pow(10.0, -3.0 * k / kBins);
}

} // namespace

TEST_CASE("compare: fully developed speckle has the exponential law's contrast, quantiles and no grain",
          "[compare]") {
    const ImageStats s = image_stats(speckle(1));
    CHECK(s.floor_fraction == 0);
    CHECK(s.contrast_intensity == Approx(1.0).margin(0.03));
    CHECK(s.contrast_amplitude == Approx(std::sqrt(4 / M_PI - 1)).margin(0.015)); // 0.5227
    for (size_t i = 0; i < kCompareQuantiles.size(); ++i)
        CHECK(s.quantiles_db[i] == Approx(10 * std::log10(-std::log(1 - kCompareQuantiles[i]))).margin(0.3));
    for (double r : s.grain_range) CHECK(std::abs(r) < 0.02);
    for (double r : s.grain_beams) CHECK(std::abs(r) < 0.02);
    double total = 0;
    for (double h : s.histogram) total += h;
    CHECK(total == Approx(1.0).margin(0.01)); // -30 ... +15 dB holds all but ~0.1 %
}

TEST_CASE("compare: K-distributed speckle has contrast sqrt(1 + 2 / alpha)", "[compare]") {
    for (double alpha : {1.0, 4.0}) {
        const ImageStats s = image_stats(speckle(2, nullptr, alpha));
        CHECK(s.contrast_intensity ==
              Approx(std::sqrt(1 + 2 / alpha)).margin(0.06 * std::sqrt(1 + 2 / alpha)));
    }
}

TEST_CASE("compare: the range profile follows the mean level, whatever the gain", "[compare]") {
    const ImageStats s = image_stats(speckle(3, falling));
    REQUIRE(s.range_profile_db.size() == 20);
    double overall = 0;
    for (int k = 0; k < kBins; ++k) overall += falling(k) / kBins;
    for (int sl = 0; sl < 20; ++sl) {
        double m = 0;
        for (int k = sl * kBins / 20; k < (sl + 1) * kBins / 20; ++k) m += falling(k) / (kBins / 20);
        CHECK(s.range_profile_db[size_t(sl)] ==
              Approx(10 * std::log10(m / overall)).margin(0.25)); // 1.6 % per slice: 0.07 dB rms
    }
    // A trend across the local window does not pass for speckle: the contrast stays the exponential law's.
    CHECK(s.contrast_intensity == Approx(1.0).margin(0.04));
}

TEST_CASE("compare: speckle correlated along range by a two-sample pulse has grain |rho|^2 = 1/4",
          "[compare]") {
    // Field f_k = (g_k + g_{k+1}) / sqrt 2 of circular complex Gaussian g: field correlation 1/2 at lag 1, 0
    // beyond; the intensity's correlation coefficient is its square.
    std::mt19937_64 rng(4);
    std::normal_distribution<double> n(0, std::sqrt(0.5));
    std::vector<std::complex<double>> g(size_t(kBins + 1) * kBeams);
    for (auto& z : g) z = {n(rng), n(rng)};
    PolarImage img;
    img.bins = kBins, img.beams = kBeams;
    for (int k = 0; k < kBins; ++k)
        for (int b = 0; b < kBeams; ++b) {
            const auto f = (g[size_t(k) * kBeams + b] + g[size_t(k + 1) * kBeams + b]) / std::sqrt(2.0);
            img.level_db.push_back(float(10 * std::log10(std::norm(f))));
        }
    const ImageStats s = image_stats(img);
    CHECK(s.grain_range[0] == Approx(0.25).margin(0.03));
    CHECK(std::abs(s.grain_range[1]) < 0.03);
    CHECK(std::abs(s.grain_beams[0]) < 0.03);
    CHECK(s.contrast_intensity == Approx(1.0).margin(0.04));
}

TEST_CASE("compare: the floor fraction counts samples at -inf", "[compare]") {
    PolarImage img = speckle(5);
    for (size_t i = 0; i < img.level_db.size(); i += 10) img.level_db[i] = -INFINITY;
    CHECK(image_stats(img).floor_fraction == Approx(0.1).epsilon(1e-12));
}

TEST_CASE("compare: pairs", "[compare]") {
    const PolarImage a = speckle(6, falling);
    const ImageStats sa = image_stats(a);
    SECTION("an image against itself with 10 dB more gain: identical statistics, correlation 1") {
        PolarImage b = a;
        for (float& v : b.level_db) v += 10;
        const PairStats p = compare_stats(a, sa, b, image_stats(b));
        CHECK(p.aligned);
        CHECK(p.profile_rms_db == Approx(0).margin(1e-4));
        CHECK(p.histogram_distance == Approx(0).margin(1e-6));
        CHECK(p.correlation == Approx(1).epsilon(1e-6));
        CHECK(p.highlight_overlap == 1);
        CHECK(p.shadow_overlap == 1);
    }
    SECTION("independent realisations of the same scene: same law, uncorrelated samples") {
        const PolarImage b = speckle(7, falling);
        const PairStats p = compare_stats(a, sa, b, image_stats(b));
        CHECK(p.histogram_distance < 0.05);
        CHECK(p.profile_rms_db < 0.15);
        // The shared 30 dB range trend correlates the dB images; the speckle itself does not: the correlation
        // is that of the trend's variance with the total's (speckle's dB variance: (10/ln 10)^2 pi^2/6).
        double mean = 0, var = 0;
        for (int k = 0; k < kBins; ++k) mean += -30.0 * k / kBins / kBins;
        for (int k = 0; k < kBins; ++k) var += std::pow(-30.0 * k / kBins - mean, 2) / kBins;
        const double speckle_var = std::pow(10 / std::log(10.0), 2) * M_PI * M_PI / 6;
        CHECK(p.correlation == Approx(var / (var + speckle_var)).margin(0.02));
    }
    SECTION("a constant image against speckle: their histograms share only the speckle in [0, 0.5) dB") {
        PolarImage c = a;
        for (float& v : c.level_db) v = 50;
        const PolarImage b = speckle(8);
        const ImageStats sc = image_stats(c);
        CHECK(sc.contrast_intensity == Approx(0).margin(1e-9));
        const PairStats p = compare_stats(c, sc, b, image_stats(b));
        const double shared = std::exp(-1.0) - std::exp(-std::pow(10.0, 0.05)); // P(1 <= X < 10^0.05)
        CHECK(p.histogram_distance == Approx(1 - shared).margin(0.01));
    }
    SECTION("different grids: no per-sample numbers") {
        PolarImage b = a;
        b.beams = kBeams / 2, b.bins = kBins * 2;
        CHECK_FALSE(compare_stats(a, sa, b, image_stats(b)).aligned);
    }
}

// Energy bookkeeping: the echo a beam's cells carry ends up, all of it and only it, in that beam's bins.
#include "support.hpp"
#include "core/scene/sampling_scheme.hpp"

#include "core/shading/physics.hpp"
#include "core/data/pose.hpp"
#include "core/scene/scene_io.hpp"
#include "core/shading/footprint.hpp"
#include "core/shading/shade.hpp"
#include "core/pipeline/simulator.hpp"

#include <algorithm>
#include "core/grid/sonar_grid.hpp"
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>

using namespace sonarsim;

namespace {

/// Range interval a cell's echo may spread over (sum of its elevation and azimuth range extents).
void footprint(const Cell& c, double& lo, double& hi) {
    lo = std::min(c.range_e_lo_m, c.range_e_hi_m) + std::min(c.range_a_lo_m, c.range_a_hi_m) - c.range_m;
    hi = std::max(c.range_e_lo_m, c.range_e_hi_m) + std::max(c.range_a_lo_m, c.range_a_hi_m) - c.range_m;
}

/// The default scene, seen from a pose where every cell lies inside [r_min, r_max).
SceneDesc inside_scene() {
    SceneDesc s = default_scene();
    s.sonar.range_min_m = 0.5, s.sonar.range_max_m = 6.0; // floor echoes reach ~2.4 m, prism ~1.6 m
    return s;
}

Cell hand_cell(float r, float e_lo, float e_hi, float a_lo, float a_hi) {
    Cell c{};
    c.range_m = r, c.range_e_lo_m = e_lo, c.range_e_hi_m = e_hi, c.range_a_lo_m = a_lo, c.range_a_hi_m = a_hi;
    c.cos_incidence = 1, c.solid_angle_sr = 1e-6;
    return c;
}

} // namespace

TEST_CASE("each beam's bins hold exactly the sum of its cells' intensities", "[energy]") {
    for (SamplingScheme scheme : {SamplingScheme::Uniform, SamplingScheme::Spread}) {
        SceneDesc s = inside_scene();
        set_scheme(s.sampling, scheme);
        s.sampling.azimuth_rays = 2;
        INFO((scheme == SamplingScheme::Spread ? "spread" : "uniform"));
        Simulator sim(s);
        const auto f = sim.render();
        const ShadeConstants k = shade_constants(s);
        const std::vector<double> edges = sonar_grid(s.sonar)->bin_edges_m();
        double worst = 0;
        size_t cells = 0, object_cells = 0;
        for (int i = 0; i < s.sonar.beams; ++i) {
            double cell_sum = 0;
            for (const Cell& c : f->hits().cells[size_t(i)]) {
                double lo, hi;
                footprint(c, lo, hi);
                if (scheme == SamplingScheme::Uniform) lo = hi = c.range_m;
                REQUIRE(lo >= s.sonar.range_min_m); // premise: nothing falls outside the window
                REQUIRE(hi < s.sonar.range_max_m);
                cell_sum += test::lin(cell_echo_db(k, material_of(s, c.material), c.range_m, c.cos_incidence,
                                                   c.solid_angle_sr));
                ++cells, object_cells += c.material != kFloorMaterial;
            }
            // The image stores L_EN as float: each bin may be off by half an ulp of its dB value.
            double bin_sum = 0, bound = 0;
            for (int b = 0; b < s.sonar.range_bins; ++b) {
                const float l = f->polar().at(b, i);
                const double e = test::lin(double(l) + s.sonar.noise_level_db);
                bin_sum += e;
                if (std::isfinite(l))
                    bound +=
                        e * std::log(10.0) / 10 * (std::nextafter(std::abs(l), INFINITY) - std::abs(l)) / 2;
            }
            INFO("beam " << i);
            CHECK(std::abs(bin_sum - cell_sum) <= 1.0001 * bound + 1e-12 * cell_sum);
            if (cell_sum > 0) worst = std::max(worst, std::abs(bin_sum / cell_sum - 1));
        }
        std::printf(
            "energy %-7s: %zu cells (%zu on the prism), worst beam |sum bins / sum cells - 1| = %.2e\n",
            scheme == SamplingScheme::Spread ? "spread" : "uniform", cells, object_cells, worst);
        CHECK(object_cells > 100); // the prism is in the picture
        CHECK(worst < 1e-6);       // float storage of the dB image: ~9e-7 at most
    }
}

TEST_CASE("cell_fraction_in sums to 1 over the bins covering each cell", "[energy]") {
    SceneDesc s = inside_scene();
    Simulator sim(s);
    const auto f = sim.render();
    const std::vector<double> edges = sonar_grid(s.sonar)->bin_edges_m();
    const double dr = edges[1] - edges[0];
    size_t checked = 0;
    double worst = 0;
    for (int i = 0; i < s.sonar.beams; i += 5)
        for (const Cell& c : f->hits().cells[size_t(i)]) {
            for (EchoBinning binning : {EchoBinning::Point, EchoBinning::Footprint}) {
                double lo, hi;
                footprint(c, lo, hi);
                const int k0 =
                    std::max(0, int(std::floor((std::min<double>(lo, c.range_m) - edges[0]) / dr)) - 1);
                const int k1 =
                    std::min(s.sonar.range_bins - 1,
                             int(std::floor((std::max<double>(hi, c.range_m) - edges[0]) / dr)) + 1);
                double sum = 0, all = 0;
                for (int b = k0; b <= k1; ++b)
                    sum += cell_fraction_in(c, binning, edges[size_t(b)], edges[size_t(b) + 1]);
                for (int b = 0; b < s.sonar.range_bins; ++b)
                    all += cell_fraction_in(c, binning, edges[size_t(b)], edges[size_t(b) + 1]);
                worst = std::max(worst, std::abs(sum - 1));
                CHECK(all == Approx(sum).margin(1e-15)); // nothing outside the footprint
            }
            ++checked;
        }
    CHECK(checked > 1000);
    CHECK(worst < 1e-12);
}

TEST_CASE("cell_fraction_in against hand values", "[energy]") {
    // Elevation extent U[1.0, 1.2] plus azimuth extent U[-0.05, 0.05] about r = 1.1: a trapezoid on
    // [0.95, 1.25] rising over 0.1 m, flat over 0.1 m, falling over 0.1 m (p = 0.1, q = 0.2).
    const Cell c = hand_cell(1.1f, 1.0f, 1.2f, 1.05f, 1.15f);
    const auto S = EchoBinning::Footprint;
    CHECK(cell_fraction_in(c, S, 0.90, 0.95) == Approx(0.0).margin(1e-6));
    CHECK(cell_fraction_in(c, S, 0.95, 1.00) == Approx(0.0625).margin(1e-6)); // x^2 / (2pq), x = 0.05
    CHECK(cell_fraction_in(c, S, 0.95, 1.05) == Approx(0.25).margin(1e-6));   // p / (2q)
    CHECK(cell_fraction_in(c, S, 1.05, 1.15) == Approx(0.5).margin(1e-6));    // flat part: 0.1 / q
    CHECK(cell_fraction_in(c, S, 1.15, 1.25) == Approx(0.25).margin(1e-6));
    CHECK(cell_fraction_in(c, S, 0.0, 10.0) == Approx(1.0).margin(1e-12));
    // The reversed edge order (range falls with elevation) gives the same distribution.
    const Cell rev = hand_cell(1.1f, 1.2f, 1.0f, 1.15f, 1.05f);
    CHECK(cell_fraction_in(rev, S, 0.95, 1.00) == Approx(0.0625).margin(1e-6));
    // No azimuth extent: a single uniform over the elevation extent.
    const Cell flat = hand_cell(1.1f, 1.0f, 1.2f, 1.1f, 1.1f);
    CHECK(cell_fraction_in(flat, S, 1.0, 1.05) == Approx(0.25).margin(1e-6));
    // Uniform: all of it in the bin that holds its range, half-open [r0, r1).
    const auto U = EchoBinning::Point;
    CHECK(cell_fraction_in(c, U, 1.0, 1.09) == 0.0);
    CHECK(cell_fraction_in(c, U, 1.09, 1.2) == 1.0);
    const Cell edge = hand_cell(1.125f, 1.0f, 1.2f, 1.1f, 1.15f);
    CHECK(cell_fraction_in(edge, U, 1.0, 1.125) == 0.0);
    CHECK(cell_fraction_in(edge, U, 1.125, 1.25) == 1.0);
}

TEST_CASE("a cell's echo spreads over its footprint with the cell's trend", "[energy]") {
    // Elevation extent U[1.0, 1.2] weighted by 1 + g (u - 1.1), plus azimuth extent U[-0.05, 0.05]: each
    // bin's share against a midpoint-rule double integral of the same density (1000 x 1000 points).
    const auto S = EchoBinning::Footprint;
    auto numeric = [](double g, double e0, double e1, double a0, double a1, double r0, double r1) {
        const int n = 1000;
        const double we = e1 - e0, wa = a1 - a0, c = 0.5 * (e0 + e1);
        double sum = 0;
        for (int i = 0; i < n; ++i) {
            const double u = e0 + (i + 0.5) * we / n, w = 1 + g * (u - c);
            for (int j = 0; j < n; ++j) {
                const double r = u + a0 + (j + 0.5) * wa / n;
                if (r >= r0 && r < r1) sum += w;
            }
        }
        return sum / (double(n) * n);
    };
    for (const double g : {2.0, -2.4}) { // |g| 0.1 <= kMaxTrend: as given
        Cell c = hand_cell(1.1f, 1.0f, 1.2f, 1.05f, 1.15f);
        c.spread_slope_per_m = float(g);
        double total = 0, mean = 0;
        for (double r0 = 0.95; r0 < 1.25 - 1e-9; r0 += 0.025) {
            const double f = cell_fraction_in(c, S, r0, r0 + 0.025);
            INFO("g " << g << " bin [" << r0 << ", " << r0 + 0.025 << ")");
            CHECK(f == Approx(numeric(g, 1.0, 1.2, -0.05, 0.05, r0, r0 + 0.025)).margin(2e-5));
            total += f, mean += f * (r0 + 0.0125);
        }
        CHECK(total == Approx(1.0).margin(1e-12));
        // The mean moves by g Var(elevation part) = g 0.2^2 / 12 (bins of 2.5 cm: their own midpoint error
        // is below 1e-5 m here).
        CHECK(mean == Approx(1.1 + g * 0.04 / 12).margin(2e-5));
        // The reversed edge order (range falls with elevation): the trend is per metre of range, the same.
        Cell rev = hand_cell(1.1f, 1.2f, 1.0f, 1.15f, 1.05f);
        rev.spread_slope_per_m = float(g);
        CHECK(cell_fraction_in(rev, S, 1.0, 1.05) == Approx(cell_fraction_in(c, S, 1.0, 1.05)).margin(1e-12));
    }
    // No azimuth extent: (1 / we) times the integral of 1 + g (u - 1.1) over the bin, in closed form.
    Cell flat = hand_cell(1.1f, 1.0f, 1.2f, 1.1f, 1.1f);
    flat.spread_slope_per_m = 2;
    CHECK(cell_fraction_in(flat, S, 1.0, 1.05) == Approx((0.05 + 2 * (0.05 * 0.05 / 2 - 0.1 * 0.05)) / 0.2));
    // A steeper trend is held at kMaxTrend: the weight 1 + 2.5 (u - 1.1) runs from 0.75 to 1.25, whatever
    // the slope's size or sign.
    for (const float g : {100.0f, 3.0f}) {
        flat.spread_slope_per_m = g;
        CHECK(cell_fraction_in(flat, S, 1.0, 1.1) == Approx((0.1 - 2.5 * 0.005) / 0.2));
    }
    flat.spread_slope_per_m = -1e30f;
    CHECK(cell_fraction_in(flat, S, 1.0, 1.1) == Approx((0.1 + 2.5 * 0.005) / 0.2));
}

TEST_CASE("the flat top of a footprint with a trend gets the shares its distribution gives", "[energy]") {
    // A grazing cell: elevation extent 0.6 m over bins of 1 cm (for_each_bin takes the bins wholly inside
    // the top without its cumulative share), azimuth extent 3 cm, either trend, either edge order.
    for (const float g : {0.6f, -0.7f})
        for (const bool reversed : {false, true}) {
            Cell c = reversed ? hand_cell(2.3f, 2.6f, 2.0f, 2.315f, 2.285f)
                              : hand_cell(2.3f, 2.0f, 2.6f, 2.285f, 2.315f);
            c.spread_slope_per_m = g;
            const double r_min = 1.5, dr = 0.01;
            const int K = 200;
            std::vector<double> got(size_t(K), 0.0);
            size_t calls = 0;
            detail::for_each_bin(c, true, K, r_min, r_min + K * dr, dr, [&](int b, double f) {
                got[size_t(b)] += f;
                ++calls;
            });
            CHECK(calls > 60);
            double sum = 0;
            for (int b = 0; b < K; ++b) {
                INFO("g " << g << " bin " << b);
                CHECK(got[size_t(b)] == Approx(cell_fraction_in(c, EchoBinning::Footprint, r_min + b * dr,
                                                                r_min + (b + 1) * dr))
                                            .margin(1e-12));
                sum += got[size_t(b)];
            }
            CHECK(sum == Approx(1.0).margin(1e-12));
        }
}

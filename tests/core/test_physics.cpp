#include "core/physics.hpp"
#include "core/pose.hpp"
#include "core/scene_io.hpp"

#include <catch2/catch.hpp>
#include <cmath>

using namespace sonarsim;

TEST_CASE("absorption reproduces the paper's Table II value", "[physics]") {
    // 0.00049 * 3000^2 * exp(-(10/27 + 0.003/17)) / 1000 = 3.0443 dB/m
    CHECK(absorption_db_per_m(3000, 10, 3) == Approx(3.0443).margin(5e-4));
    CHECK(absorption_db_per_m(3000, 10, 3) == Approx(3.04).margin(0.005));
}

TEST_CASE("transmission loss is 20 log10 R + alpha R", "[physics]") {
    CHECK(transmission_loss_db(1.0, 3.0) == Approx(3.0));
    CHECK(transmission_loss_db(10.0, 0.5) == Approx(25.0));
}

TEST_CASE("GSAB backscatter against hand values", "[physics]") {
    Material m; // nu -45 dB, q 2, mu 0
    CHECK(backscatter_db(m, 1.0) == Approx(-45.0));
    CHECK(backscatter_db(m, 0.5) == Approx(-45.0 + 20 * std::log10(0.5)));
    m.mu = 1.0, m.h_deg = 10.0;
    // theta = 0: 10 log10(1 + 10^-4.5)
    CHECK(backscatter_db(m, 1.0) == Approx(10 * std::log10(1 + std::pow(10, -4.5))));
    const double th = deg2rad(10.0), c = std::cos(th);
    CHECK(backscatter_db(m, c) ==
          Approx(10 * std::log10(std::exp(-0.5) + std::pow(10, -4.5) * c * c)).epsilon(1e-9));
}

TEST_CASE("Fig. 9 pose 1 sees the prism centre at +0.45 deg, 1.68 m", "[pose]") {
    const SceneDesc s = default_scene();
    const Polar p = world_to_sonar_polar(s.sonar.pose, to_glm(s.objects[0].position_m));
    CHECK(p.azimuth_deg == Approx(0.45).margin(0.05));
    CHECK(p.range_m == Approx(1.68).margin(0.005));
}

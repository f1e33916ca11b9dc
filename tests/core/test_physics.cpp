#include "core/shading/physics.hpp"
#include "core/shading/shade.hpp"
#include "core/geometry/geometry.hpp"
#include "core/data/pose.hpp"
#include "core/scene/scene_io.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

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

TEST_CASE("absorption follows eq. 7 in f, T and D", "[physics]") {
    // f in kHz, T in degC, D in km: 0.00049 f^2 exp(-(T/27 + D/17)) / 1000
    CHECK(absorption_db_per_m(1000, 0, 0) == Approx(0.49).epsilon(1e-12));
    CHECK(absorption_db_per_m(2000, 27, 0) == Approx(4 * 0.49 / std::exp(1.0)).epsilon(1e-12));
    CHECK(absorption_db_per_m(1000, 0, 17000) == Approx(0.49 / std::exp(1.0)).epsilon(1e-12));
    // Depth in metres enters as D/1000 km: 3 m changes alpha by a factor exp(-3/17000) only.
    CHECK(absorption_db_per_m(3000, 10, 3) / absorption_db_per_m(3000, 10, 0) ==
          Approx(std::exp(-3.0 / 17000)).epsilon(1e-12));
}

TEST_CASE("transmission loss against hand values", "[physics]") {
    // 2 m at Table II's alpha: 20 log10 2 + 2 * 3.04 = 6.0206 + 6.08
    CHECK(transmission_loss_db(2.0, 3.04) == Approx(12.10060).margin(1e-5));
    CHECK(transmission_loss_db(0.1, 0.0) == Approx(-20.0));
    CHECK(transmission_loss_db(4.0, 1.5) == Approx(12.04120 + 6.0).margin(1e-5));
}

TEST_CASE("GSAB: Lambert exponent, specular lobe and no return", "[physics]") {
    Material m;
    m.nu_db = -30, m.q = 4;
    CHECK(backscatter_db(m, 0.5) == Approx(-30 + 40 * std::log10(0.5)).epsilon(1e-12));
    m.q = 0; // Lambert term constant
    CHECK(backscatter_db(m, 0.01) == Approx(-30.0).epsilon(1e-12));
    // Specular term alone dominates near normal incidence: mu = 0.1, h = 5 deg, theta = 3 deg.
    m.q = 2, m.nu_db = -45, m.mu = 0.1, m.h_deg = 5;
    const double th = 3 * kPi / 180, h = 5 * kPi / 180;
    const double s =
        0.1 * std::exp(-th * th / (2 * h * h)) + std::pow(10, -4.5) * std::cos(th) * std::cos(th);
    CHECK(backscatter_db(m, std::cos(th)) == Approx(10 * std::log10(s)).epsilon(1e-10));
    // mu = 0 turns it off exactly (the paper's default).
    m.mu = 0;
    CHECK(backscatter_db(m, std::cos(th)) == Approx(-45 + 20 * std::log10(std::cos(th))).epsilon(1e-12));
    // Nothing returns from behind the surface or exactly at grazing incidence.
    CHECK(backscatter_db(m, 0.0) == -std::numeric_limits<double>::infinity());
    CHECK(backscatter_db(m, -0.3) == -std::numeric_limits<double>::infinity());
}

TEST_CASE("one cell's echo level is L_S - 2 TL + L_BS + 10 log10(r^2 dOmega / cos)", "[physics]") {
    const ShadeConstants k{230.0, 10.0, 3.04, 0.0};
    Material m; // nu -45 dB, q 2
    const double r = 2.0, c = 0.5, dom = 1e-6;
    const double expect = 230 - 2 * (20 * std::log10(r) + 3.04 * r) + (-45 + 20 * std::log10(c)) +
                          10 * std::log10(r * r * dom / c);
    CHECK(cell_echo_db(k, m, r, c, dom) == Approx(expect).epsilon(1e-12));
    CHECK(cell_echo_db(k, m, r, 0.0, dom) == -std::numeric_limits<double>::infinity());
    CHECK(cell_echo_db(k, m, 0.0, c, dom) == -std::numeric_limits<double>::infinity());
    // Every exponent q (q = 1 and 2 take one logarithm, the others two): L_BS = nu + 10 q log10 cos.
    for (const double q : {0.0, 1.0, 1.5, 2.0, 3.0}) {
        INFO("q " << q);
        m.q = q;
        const double expect_q = 230 - 2 * (20 * std::log10(r) + 3.04 * r) + (-45 + 10 * q * std::log10(c)) +
                                10 * std::log10(r * r * dom / c);
        CHECK(cell_echo_db(k, m, r, c, dom) == Approx(expect_q).epsilon(1e-12));
    }
    // The noise level does not enter a cell's echo; shade_constants carries it with L_S and alpha.
    const ShadeConstants d = shade_constants(SceneDesc{});
    CHECK(d.source_level_db == 230.0);
    CHECK(d.noise_level_db == 10.0);
    CHECK(d.alpha_db_per_m == Approx(3.0443).margin(5e-4));
}

TEST_CASE(
    "the water surface's coherent reflection loss is the Kirchhoff (Eckart) |R|^2 = exp(-(2 k sigma cos)^2)",
    "[physics][multipath]") {
    SceneDesc s;
    s.water.surface_height_m = 2.0;
    const ShadeConstants k = shade_constants(s);
    const double c = sound_speed_m_s(s.water.temperature_c, s.water.depth_m);
    REQUIRE(k.wavenumber_rad_per_m == Approx(2 * kPi * s.sonar.frequency_khz * 1e3 / c).epsilon(1e-12));
    // Choose sigma so that the Rayleigh parameter 2 k sigma cos is 1 at normal incidence: the amplitude
    // exp(-2 k^2 sigma^2 cos^2) = exp(-1/2), so |R|^2 = 1/e, -4.343 dB (not 1/e^2, -8.686 dB).
    s.water.surface_roughness_m = 1 / (2 * k.wavenumber_rad_per_m);
    CHECK(reflection_gain_db(k, s, kSurfaceMaterial, 1.0) ==
          Approx(-10 * std::log10(std::exp(1.0))).epsilon(1e-12));
    for (double cos_inc : {0.0, 0.25, 0.5, 0.9}) {
        const double amplitude =
            std::exp(-2 * std::pow(k.wavenumber_rad_per_m * s.water.surface_roughness_m * cos_inc, 2));
        CHECK(reflection_gain_db(k, s, kSurfaceMaterial, cos_inc) ==
              Approx(20 * std::log10(amplitude)).margin(1e-12));
    }
    s.water.surface_roughness_m = 0; // a smooth pressure-release surface loses nothing
    CHECK(reflection_gain_db(k, s, kSurfaceMaterial, 0.7) == 0.0);
    // Other mirrors lose their reflection_db, whatever the roughness.
    s.seafloor->material.reflection_db = 6;
    CHECK(reflection_gain_db(k, s, kFloorMaterial, 0.7) == -6.0);
}

TEST_CASE("a ghost's echo level: L_S - 2 alpha r - 20 log10 leg + 10 log10(dOmega / cos) + L_BS + mirrors",
          "[physics][multipath]") {
    // A scatterer (object 1) seen by way of one mirror: an object with reflection_db, or the rough water
    // surface (|R|^2 = exp(-(2 k sigma cos)^2)). Double path: both legs by the mirror (its loss twice),
    // L_BS = nu + 10 q log10 cos_in; mixed: one leg each way, nu + 5 q log10(cos_in cos_out), the loss once.
    SceneDesc s;
    s.water.surface_roughness_m = 0.01;
    s.objects.resize(2);
    s.objects[1].material.reflection_db = 4.5; // object 2: the mirror
    const ShadeConstants k{220.0, 10.0, 0.8, 3000.0};
    const double r = 7.5, leg = 9.0, cos_in = 0.6, cos_out = 0.35, dom = 2e-6, cos_m = 0.8;
    GhostCell g;
    g.cell.range_m = float(r), g.cell.cos_incidence = float(cos_in), g.cell.solid_angle_sr = float(dom);
    g.cell.material = 1;
    g.other_leg_m = float(leg), g.cos_other = float(cos_out);
    g.mirror_cos[0] = float(cos_m);
    const double rough_db = -10 / std::log(10.0) * std::pow(2 * 3000.0 * 0.01 * double(float(cos_m)), 2);
    for (const unsigned mirror : {2u, kSurfaceMaterial})
        for (const bool mixed : {false, true})
            for (const double q : {0.0, 1.0, 1.5, 2.0, 3.0}) {
                INFO("mirror " << mirror << " mixed " << mixed << " q " << q);
                s.objects[0].material.q = q, s.objects[0].material.nu_db = -30;
                g.mirror_material[0] = mirror;
                g.tx_bounces = 1, g.rx_bounces = mixed ? 0 : 1;
                const double ci = double(float(cos_in)), co = double(float(cos_out));
                const double bs_db = -30 + (mixed ? 5 * q * std::log10(ci * co) : 10 * q * std::log10(ci));
                const double mirror_db = mirror == kSurfaceMaterial ? rough_db : -4.5;
                const double expect = 220 - 2 * 0.8 * double(float(r)) - 20 * std::log10(double(float(leg))) +
                                      10 * std::log10(double(float(dom)) / ci) + bs_db +
                                      (mixed ? 1 : 2) * mirror_db;
                CHECK(ghost_echo_db(k, s, g) == Approx(expect).epsilon(1e-12));
            }
    // The specular term (mu > 0) enters a double path's backscatter (GSAB), not a mixed one's.
    s.objects[0].material.q = 2, s.objects[0].material.mu = 0.05, s.objects[0].material.h_deg = 6;
    g.mirror_material[0] = 2u, g.tx_bounces = 1, g.rx_bounces = 1;
    const double ci = double(float(cos_in)), co = double(float(cos_out));
    const double common = 220 - 2 * 0.8 * double(float(r)) - 20 * std::log10(double(float(leg))) +
                          10 * std::log10(double(float(dom)) / ci);
    CHECK(ghost_echo_db(k, s, g) ==
          Approx(common + backscatter_db(s.objects[0].material, ci) - 9).epsilon(1e-12));
    g.rx_bounces = 0;
    CHECK(ghost_echo_db(k, s, g) == Approx(common - 30 + 10 * std::log10(ci * co) - 4.5).epsilon(1e-12));
    // Nothing returns at grazing incidence on either leg.
    g.cos_other = 0;
    CHECK(ghost_echo_db(k, s, g) == -std::numeric_limits<double>::infinity());
}

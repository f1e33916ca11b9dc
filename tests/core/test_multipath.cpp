// Multipath (issue 12): ghosts where the image-source method puts them, at the levels spreading, absorption
// and |R|^2 predict; the floor's first multiple by way of the surface; nothing changes without bounces or
// mirrors; the energy of each path order adds up to the image's.
#include "support.hpp"
#include "core/io/output.hpp"
#include "core/scene/sampling_scheme.hpp"

#include "core/analysis/reference.hpp"
#include "core/shading/ground_truth.hpp"
#include "core/shading/physics.hpp"
#include "core/data/pose.hpp"
#include "core/scene/scene_io.hpp"
#include "core/pipeline/simulator.hpp"

#include <catch2/catch.hpp>
#include <cmath>

using namespace sonarsim;
using namespace sonarsim::test;

namespace {
Channels path_orders() {
    Channels c;
    c.path_orders = true;
    return c;
}
} // namespace

namespace {

/// A sonar at the origin looking along +x under a flat surface 1 m above it, a small square plate facing
/// it 4 m away and 0.2 m up: the image sonar is at z = 2, the plate's image at z = 1.8 (24 deg up: inside
/// the +-30 deg aperture).
SceneDesc plate_under_surface() {
    SceneDesc s;
    s.seafloor.reset();
    s.sonar.pose.position_m = {0, 0, 0};
    s.sonar.pose.orientation_deg = {0, 0, 0};
    s.sonar.frequency_khz = 500;
    s.sonar.azimuth_fov_deg = 20, s.sonar.elevation_fov_deg = 60;
    s.sonar.beams = 64;
    s.sonar.range_min_m = 3.5, s.sonar.range_max_m = 5.0, s.sonar.range_bins = 300; // 5 mm bins
    s.water.surface_height_m = 1.0;
    s.water.surface_material.nu_db = -200; // its own backscatter out of the way
    s.sampling.bounces = 1;
    ObjectDesc plate;
    plate.box_m = Vec3d{0.002, 0.2, 0.2};
    plate.position_m = {4.0, 0.0, 0.2};
    plate.material.nu_db = -10, plate.material.q = 2;
    s.objects.push_back(plate);
    return s;
}

double sum_lin(const std::vector<double>& v) {
    double t = 0;
    for (double x : v) t += x;
    return t;
}

/// Energy-weighted mean range of an intensity image (bins x beams) over the rows whose centre is in
/// [r0, r1).
double mean_range(const std::vector<double>& e, const SceneDesc& s, double r0, double r1) {
    const double dr = (s.sonar.range_max_m - s.sonar.range_min_m) / s.sonar.range_bins;
    double w = 0, wr = 0;
    for (int b = 0; b < s.sonar.range_bins; ++b) {
        const double r = s.sonar.range_min_m + (b + 0.5) * dr;
        if (r < r0 || r >= r1) continue;
        for (int i = 0; i < s.sonar.beams; ++i)
            w += e[size_t(b) * s.sonar.beams + i], wr += r * e[size_t(b) * s.sonar.beams + i];
    }
    return w > 0 ? wr / w : -1;
}

} // namespace

TEST_CASE("ghosts of a plate under the surface at the image-source ranges and levels", "[multipath]") {
    for (double roughness_m : {0.0, 0.0002}) {
        SceneDesc s = plate_under_surface();
        s.water.surface_roughness_m = roughness_m;
        INFO("surface roughness " << roughness_m << " m");
        Simulator sim(s);
        const auto frame = sim.render();
        const TraceResult& hits = *frame->hits_ptr;

        // The closed forms: the plate's centre P, its normal -x, the sonar S and its image S'.
        const double A = 0.2 * 0.2, nu = -10, c = sound_speed_m_s(s.water.temperature_c, s.water.depth_m);
        const double alpha =
            absorption_db_per_m(s.sonar.frequency_khz, s.water.temperature_c, s.water.depth_m);
        const double r = std::hypot(4.0, 0.2), L = std::hypot(4.0, 1.8); // S -> P, S' -> P
        const double cos_d = 4.0 / r, cos_i = 4.0 / L;                   // incidence on the plate
        // |R|^2 at the mirror point: the ray from S' to P meets the surface at incidence cos = 1.8 / L.
        const double k = 2 * kPi * s.sonar.frequency_khz * 1e3 / c, g = 2 * k * roughness_m * (1.8 / L);
        const double R_db = 10 * std::log10(std::exp(-g * g));
        const double SL = s.sonar.source_level_db;
        const double direct_db =
            SL - 40 * std::log10(r) - 2 * alpha * r + nu + 20 * std::log10(cos_d) + 10 * std::log10(A);
        const double double_db = SL - 40 * std::log10(L) - 2 * alpha * L + nu + 20 * std::log10(cos_i) +
                                 10 * std::log10(A) + 2 * R_db;
        const double one_mixed_db = SL - 20 * std::log10(r) - 20 * std::log10(L) - alpha * (r + L) + nu +
                                    10 * std::log10(cos_d) + 10 * std::log10(cos_i) + 10 * std::log10(A) +
                                    R_db;
        const double mixed_db = one_mixed_db + 10 * std::log10(2.0); // out by the mirror or back by it

        // Energy per path order: 0 direct, 1 mixed (both), 2 double. Measured within 0.05 dB of the closed
        // forms (the issue asks for 0.5 dB).
        const std::vector<double> order_db = accumulate(hits, s, path_orders()).path_order_db;
        REQUIRE(order_db.size() == 3);
        CHECK(order_db[0] == Approx(direct_db).margin(0.1));
        CHECK(order_db[1] == Approx(mixed_db).margin(0.1));
        CHECK(order_db[2] == Approx(double_db).margin(0.1));
        INFO("direct " << order_db[0] << " / " << direct_db << ", mixed " << order_db[1] << " / " << mixed_db
                       << ", double " << order_db[2] << " / " << double_db);

        // Where they appear: the image without the ghosts subtracted from the image with them leaves the
        // ghosts alone; each lies within one bin of half its path length.
        SceneDesc direct_only = s;
        direct_only.sampling.bounces = 0;
        Simulator sim0(direct_only);
        const std::vector<double> e1 = echo_intensity(frame->polar(), s.sonar.noise_level_db);
        const std::vector<double> e0 = echo_intensity(sim0.render()->polar(), s.sonar.noise_level_db);
        std::vector<double> ghosts(e1.size());
        for (size_t n = 0; n < e1.size(); ++n) ghosts[n] = std::max(0.0, e1[n] - e0[n]);
        const double bin_m = 1.5 / 300, half_mixed = 0.5 * (r + L);
        CHECK(std::abs(mean_range(e0, s, r - 0.08, r + 0.08) - r) < bin_m);
        CHECK(std::abs(mean_range(ghosts, s, half_mixed - 0.08, half_mixed + 0.08) - half_mixed) < bin_m);
        CHECK(std::abs(mean_range(ghosts, s, L - 0.08, L + 0.08) - L) < bin_m);
        // And nothing else: the ghosts' energy is the two ghost orders'.
        CHECK(10 * std::log10(sum_lin(ghosts)) ==
              Approx(10 * std::log10(lin(order_db[1]) + lin(order_db[2]))).margin(0.05));
    }
}

TEST_CASE("the floor's first multiple by way of the surface starts at its image-source range",
          "[multipath]") {
    // A sonar 1 m above the floor and 1 m below the surface looking up 20 deg (+-7 deg): its rays meet the
    // surface only, and come down to the floor from there. The floor seen in the surface lies 3 m above the
    // sonar, so its echo starts where the aperture's top edge meets it: 3 / sin 27 deg.
    SceneDesc s;
    s.objects.clear();
    s.seafloor->height_m = 0;
    s.water.surface_height_m = 2.0;
    s.sonar.pose.position_m = {0, 0, 1.0};
    s.sonar.pose.orientation_deg = {0, -20, 0};
    s.sonar.frequency_khz = 1000;
    s.sonar.range_min_m = 1.0, s.sonar.range_max_m = 9.0, s.sonar.range_bins = 800; // 1 cm bins
    s.sampling.bounces = 1;
    Simulator sim(s);
    const auto frame = sim.render();
    const PolarImage& img = frame->polar();
    const GroundTruth gt = compute_ground_truth(*frame->hits_ptr, s);
    const int centre = s.sonar.beams / 2; // the beam just off the axis: its top edge is 27 deg up
    const double top_e = deg2rad(27.0), expected = 3.0 / std::sin(top_e), bin_m = 0.01;
    int first = -1;
    for (int b = 0; b < img.bins && first < 0; ++b) {
        const size_t at = size_t(b) * img.beams + centre;
        if (std::isfinite(img.at(b, centre)) && gt.bounces[at] > 0) first = b;
    }
    REQUIRE(first >= 0);
    const double first_m = s.sonar.range_min_m + first * bin_m;
    CHECK(std::abs(first_m + 0.5 * bin_m - expected) < 1.5 * bin_m); // the bin holding 3 / sin 27 deg
    // Before it, only the surface's own echo (2.2 m ... 4.4 m); beyond it, the floor seen twice by way of
    // the surface: double paths (two reflections).
    CHECK(gt.object_id[size_t(first + 5) * img.beams + centre] == 0);
    CHECK(gt.bounces[size_t(first + 5) * img.beams + centre] == 2);
    CHECK(gt.object_id[size_t(int((3.0 - 1.0) / bin_m)) * img.beams + centre] == -2);
    // Without the surface as a mirror path the sonar sees nothing beyond the surface's echo.
    SceneDesc direct = s;
    direct.sampling.bounces = 0;
    Simulator sim0(direct);
    const PolarImage& img0 = sim0.render()->polar();
    CHECK(!std::isfinite(img0.at(first + 5, centre)));
}

TEST_CASE("without bounces or mirrors the image is unchanged byte for byte", "[multipath]") {
    // Same rays and shading whether multipath is off (bounces 0) or on with nothing to reflect.
    SceneDesc plain = default_scene(), on = plain;
    on.sampling.bounces = 2;
    CHECK(encode_npy(Simulator(plain).render()->polar()) == encode_npy(Simulator(on).render()->polar()));
    // Mirrors with bounces 0: only the mirrors' own backscatter, as before.
    SceneDesc mirrors = plain;
    mirrors.seafloor->material.reflection_db = 3;
    mirrors.objects[0].material.reflection_db = 0;
    CHECK(encode_npy(Simulator(plain).render()->polar()) == encode_npy(Simulator(mirrors).render()->polar()));
}

TEST_CASE("the tank's ghosts at one ray column per beam are close to those at nine", "[multipath]") {
    // A ghost arriving from its scatterer spans the beams that see the scatterer's footprint; each beam's
    // share must spread over its own part of the footprint's range, or the ghost's edges smear by a
    // beam's width (first order in the column width: 18 % here, against 6.5 % now).
    SceneDesc s = load_scene(std::string(SONARSIM_ASSETS) + "/scenes/tank.json");
    set_scheme(s.sampling, SamplingScheme::Spread);
    s.sampling.elevation_rays = 243;
    auto ghosts = [&](int columns) { // the image with ghosts less the direct image, linear
        s.sampling.azimuth_rays = columns;
        s.sampling.bounces = 1;
        std::vector<double> all = echo_intensity(Simulator(s).render()->ideal(), s.sonar.noise_level_db);
        s.sampling.bounces = 0;
        const std::vector<double> direct =
            echo_intensity(Simulator(s).render()->ideal(), s.sonar.noise_level_db);
        for (size_t n = 0; n < all.size(); ++n) all[n] -= direct[n];
        return all;
    };
    const std::vector<double> one = ghosts(1), nine = ghosts(9);
    REQUIRE(sum_lin(nine) > 0);
    const double err = relative_l1(one, nine);
    INFO("ghosts' rel L1, one column per beam against nine: " << err);
    CHECK(err < 0.10);
}

TEST_CASE("both estimates see the tank's ghosts' error and strict refines it", "[multipath]") {
    // Two bounces in the tank, against spread 729 x 9 (itself 0.13 % off 729 x 27). One ray column per beam
    // leaves the ghosts 1.5 % off. The azimuth probe brings the probed cells' ghosts, so both estimates see
    // that error (before the probe, fast said 0.43 %): fast reports it (1.7 %, tolerance not met); strict
    // takes three columns per beam for every group (a pass's ghosts are the whole image's) and ends within
    // the tolerance: 0.43 %, estimated 0.44 %.
    SceneDesc s = load_scene(std::string(SONARSIM_ASSETS) + "/scenes/tank.json");
    s.sampling.bounces = 2;
    const SceneGeometry g(s);
    SceneDesc dense = s;
    set_scheme(dense.sampling, SamplingScheme::Spread);
    dense.sampling.elevation_rays = 729, dense.sampling.azimuth_rays = 9;
    const PolarImage ref = shade(trace(g, dense), dense);
    auto measure = [&](ErrorEstimate how) {
        SceneDesc a = s;
        a.sampling.estimate = how;
        const TraceResult t = trace(g, a);
        CHECK(t.error_estimate.strict == (how == ErrorEstimate::Strict));
        CHECK(t.error_estimate.meets(a.sampling) == (how == ErrorEstimate::Strict));
        return std::make_tuple(t.error_estimate.rel_l1, compare_images(shade(t, a), ref).rel_l1,
                               t.error_estimate.azimuth_rel_l1);
    };
    const auto [fast_est, fast_err, fast_az] = measure(ErrorEstimate::Fast);
    const auto [strict_est, strict_err, strict_az] = measure(ErrorEstimate::Strict);
    INFO("fast: estimate " << fast_est << " (azimuth " << fast_az << ") measured " << fast_err
                           << "; strict: estimate " << strict_est << " measured " << strict_err);
    CHECK(fast_err > s.sampling.tolerance_rel_l1);
    CHECK(fast_est > 0.8 * fast_err); // within the reference's own error of honest
    CHECK(fast_est < 3 * fast_err);
    CHECK(fast_az > 0);
    CHECK(strict_err < s.sampling.tolerance_rel_l1);
    CHECK(strict_est > 0.8 * strict_err);
    CHECK(strict_est < 3 * strict_err);
    CHECK(strict_az == 0);
}

TEST_CASE("a trace of some beams estimates its ghosts' error from the ghosts arriving in its sample beams",
          "[multipath]") {
    // Motion during a frame traces each ping's beams alone (TraceControl::beams). The coarser image of each
    // sample beam must hold the ghosts arriving in that beam; held by slot instead (the k-th traced beam got
    // beam k's ghosts), the estimate compared unrelated ghosts and read 13 % for a 4.6 % image, tracing 7x
    // the rays.
    SceneDesc s = load_scene(std::string(SONARSIM_ASSETS) + "/scenes/tank.json");
    const SceneGeometry g(s);
    std::vector<char> every_fourth(size_t(s.sonar.beams), 0);
    for (size_t i = 0; i < every_fourth.size(); i += 4) every_fourth[i] = 1;
    TraceControl some;
    some.beams = &every_fourth;
    const TraceResult all = trace(g, s), part = trace(g, s, some);
    INFO("estimated rel L1: all beams " << all.error_estimate.rel_l1 << ", every 4th "
                                        << part.error_estimate.rel_l1);
    CHECK(part.error_estimate.rel_l1 < 3 * all.error_estimate.rel_l1);
    CHECK(part.rays_traced < all.rays_traced);
}

TEST_CASE("energy is accounted per path order", "[multipath]") {
    // The tank: walls, floor and surface mirrors, two targets. Same rays (spread scheme) with and without
    // multipath, so the direct order must equal the image without bounces, and the orders sum to the image.
    SceneDesc s = load_scene(std::string(SONARSIM_ASSETS) + "/scenes/tank.json");
    set_scheme(s.sampling, SamplingScheme::Spread);
    s.sampling.elevation_rays = 101;
    for (int bounces : {1, 2}) {
        s.sampling.bounces = bounces;
        INFO("bounces " << bounces);
        Simulator sim(s);
        const auto frame = sim.render();
        const std::vector<double> order_db = frame->path_order_db;
        REQUIRE(order_db.size() == size_t(2 * bounces + 1));
        double orders = 0;
        for (double o : order_db) orders += lin(o);
        const double image = sum_lin(echo_intensity(frame->ideal(), s.sonar.noise_level_db));
        CHECK(orders == Approx(image).epsilon(1e-4));
        SceneDesc direct = s;
        direct.sampling.bounces = 0;
        const double direct_image =
            sum_lin(echo_intensity(Simulator(direct).render()->ideal(), s.sonar.noise_level_db));
        CHECK(lin(order_db[0]) == Approx(direct_image).epsilon(1e-6));
        // Paths out and back by one chain of mirrors (orders 2 k) or by it one way and directly the other
        // (order k) carry energy in the tank, each reflection costing at least the walls' 3 dB; paths whose
        // two legs take different chains (order 3) are not followed.
        for (size_t o = 1; o < order_db.size(); ++o) {
            INFO("order " << o << ": " << order_db[o] << " dB, direct " << order_db[0] << " dB");
            if (o == 3) {
                CHECK(!std::isfinite(order_db[o]));
                continue;
            }
            CHECK(std::isfinite(order_db[o]));
            CHECK(order_db[o] < order_db[0]);
        }
        // Ghosts add energy: the image is brighter than the direct one.
        CHECK(image > direct_image);
    }
}

TEST_CASE("a path order's echo far below its beam's peak is still counted", "[multipath][stiff]") {
    // One beam: a direct cell 1 m away and a double-path ghost 700 m away, whose two-way absorption
    // (2 x 3 dB/m x 700 m) puts it ~4000 dB below: beyond what exp() resolves against the peak (~3200 dB),
    // so its order's sum takes the log-domain path. Each order holds one contribution: its own level.
    SceneDesc s;
    s.seafloor.reset();
    s.sonar.beams = 1, s.sonar.range_min_m = 0.5, s.sonar.range_max_m = 800, s.sonar.range_bins = 1000;
    s.sampling.bounces = 1;
    s.objects.resize(1); // material 1: Lambertian, nu -45 dB
    s.objects[0].material.reflection_db = 3;
    const ShadeConstants k = shade_constants(s);
    auto point_cell = [](double r_m) {
        Cell c{};
        c.range_m = float(r_m), c.cos_incidence = 0.7f, c.solid_angle_sr = 1e-5f, c.material = 1;
        c.range_e_lo_m = c.range_e_hi_m = c.range_a_lo_m = c.range_a_hi_m = float(r_m);
        return c;
    };
    TraceResult hits;
    hits.beams = 1;
    hits.cells = {{point_cell(1.0)}};
    GhostCell g;
    g.cell = point_cell(700.0);
    g.other_leg_m = 700, g.cos_other = 0.7f, g.tx_bounces = g.rx_bounces = 1, g.mirror_material[0] = 1;
    hits.ghosts = {{g}};
    const Material& m = material_of(s, 1);
    const double direct_db = cell_echo_db(k, m, 1.0, double(0.7f), double(1e-5f)),
                 ghost_db = ghost_echo_db(k, s, g);
    REQUIRE(direct_db - ghost_db > 3300);
    const std::vector<double> order_db = accumulate(hits, s, path_orders()).path_order_db;
    REQUIRE(order_db.size() == 3);
    CHECK(order_db[0] == Approx(direct_db).epsilon(1e-12));
    CHECK(order_db[1] == -std::numeric_limits<double>::infinity());
    CHECK(order_db[2] == Approx(ghost_db).epsilon(1e-12));
}

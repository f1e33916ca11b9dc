// Stiff and extreme inputs give finite, correct images: no NaN, no +inf, -inf only where nothing echoes.
#include "core/shading/physics.hpp"
#include "core/scene/sampling_scheme.hpp"
#include "core/analysis/reference.hpp"
#include "core/scene/scene_io.hpp"
#include "core/pipeline/simulator.hpp"
#include "core/sampling/trace.hpp"
#include "core/shading/accumulate.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>

using namespace sonarsim;

namespace {

SceneDesc floor_scene(double height_m, Vec3d orientation_deg,
                      SamplingScheme scheme = SamplingScheme::Adaptive) {
    SceneDesc s;
    s.objects.clear();
    s.seafloor = Seafloor{};
    s.sonar.pose.position_m = {0, 0, height_m};
    s.sonar.pose.orientation_deg = orientation_deg;
    set_scheme(s.sampling, scheme);
    return s;
}

PolarImage render(const SceneDesc& s) {
    Simulator sim(s);
    return sim.render()->polar();
}

/// No NaN, no +inf anywhere; returns the number of echoing (finite) bins.
long check_finite(const PolarImage& img) {
    long finite = 0, nan = 0, pos_inf = 0;
    for (float v : img.level_db) {
        nan += std::isnan(v);
        pos_inf += v == INFINITY;
        finite += std::isfinite(v);
    }
    REQUIRE(nan == 0);
    REQUIRE(pos_inf == 0);
    return finite;
}

/// The floor reference with `panels` x 8 Gauss-Legendre azimuth nodes per beam (16 resolve a 0.05 deg lobe).
ImageError against_floor_reference(const SceneDesc& s, int panels = 4) {
    const PolarImage img = render(s), ref = floor_reference(s, panels);
    REQUIRE(check_finite(img) > 0);
    REQUIRE(check_finite(ref) > 0);
    const ImageError e = compare_images(img, ref);
    INFO("rel L1 " << e.rel_l1 << ", median " << e.median_abs_db << " dB, holes " << e.holes << "/"
                   << e.echoing_ref << ", spurious " << e.spurious);
    return e;
}

std::string write_text(const std::string& name, const std::string& text) {
    const std::string path = std::string(SONARSIM_TEST_OUT) + "/" + name;
    std::ofstream(path) << text;
    return path;
}

} // namespace

TEST_CASE("grazing: floor a few mm below a level sonar, q = 0 (singular area term)", "[stiff]") {
    for (double q : {0.0, 1.0, 2.0}) {
        SceneDesc s = floor_scene(0.02, {0, 0, 0});
        s.seafloor->material.q = q;
        const ImageError e = against_floor_reference(s);
        CHECK(e.rel_l1 < 0.01);
        CHECK(e.median_abs_db < 0.05);
    }
}

TEST_CASE("sonar exactly at floor level sees nothing and stays finite", "[stiff]") {
    SceneDesc s = floor_scene(0.0, {0, 0, 0});
    const PolarImage img = render(s);
    CHECK(check_finite(img) == 0);
}

TEST_CASE("narrow specular lobe at normal incidence, h down to 0.05 deg", "[stiff]") {
    for (double h : {5.0, 0.5, 0.05}) {
        SceneDesc s = floor_scene(2.0, {0, 90, 0}); // looking straight down: normal incidence at the centre
        s.seafloor->material.mu = 1.0, s.seafloor->material.h_deg = h;
        s.sonar.range_min_m = 1.5, s.sonar.range_max_m = 2.5, s.sonar.range_bins = 200;
        const ImageError e = against_floor_reference(s, 16);
        INFO("h = " << h);
        CHECK(e.rel_l1 < 0.01);
        CHECK(e.holes == 0);
    }
}

TEST_CASE("Lambert exponent q from 0 to 100 and nu from -80 to 0 dB", "[stiff]") {
    for (double q : {0.0, 0.5, 10.0, 100.0})
        for (double nu : {-80.0, -45.0, 0.0}) {
            SceneDesc s = floor_scene(1.0, {0, 30, 0});
            s.seafloor->material.q = q, s.seafloor->material.nu_db = nu;
            const ImageError e = against_floor_reference(s);
            INFO("q = " << q << ", nu = " << nu);
            CHECK(e.rel_l1 < 0.005);
            CHECK(e.median_abs_db < 0.02);
        }
}

TEST_CASE("absorption up to ~55 dB/m: f = 10 MHz, T = -2 C, no underflow", "[stiff]") {
    const double alpha = absorption_db_per_m(10000, -2, 0);
    CHECK(alpha == Approx(0.00049 * 1e8 * std::exp(2.0 / 27) / 1000).epsilon(1e-12));
    CHECK(alpha > 50);
    for (double t : {-2.0, 35.0}) { // the absorption formula's range: T in [-2, 35] degC
        SceneDesc s = floor_scene(1.0, {0, 30, 0});
        s.sonar.frequency_khz = 10000, s.water.temperature_c = t, s.water.depth_m = 0;
        const ImageError e = against_floor_reference(s);
        // Linear intensities near r_max are ~10^-50 of those near r_min: each bin must still be right in dB.
        CHECK(e.p95_abs_db < 0.05);
        CHECK(e.holes == 0);
    }
}

TEST_CASE("r_min -> 0: echoes from a floor right under the sonar", "[stiff]") {
    SceneDesc s = floor_scene(0.05, {0, 60, 0});
    s.sonar.range_min_m = 0.0, s.sonar.range_max_m = 0.5, s.sonar.range_bins = 256;
    const ImageError e = against_floor_reference(s);
    CHECK(e.rel_l1 < 0.01);
}

TEST_CASE("sonar inside a mesh: a 20 m box whose bottom is the floor equals the bare floor", "[stiff]") {
    SceneDesc bare = floor_scene(1.0, {0, 30, 0});
    SceneDesc boxed = bare;
    boxed.seafloor.reset();
    ObjectDesc room;
    room.box_m = Vec3d{20, 20, 20};
    room.position_m = {0, 0, 10}; // bottom face at z = 0, walls 10 m away (beyond r_max)
    room.material = bare.seafloor->material;
    boxed.objects.push_back(room);
    const PolarImage ref = floor_reference(bare, 16), img = render(boxed);
    check_finite(img);
    const ImageError e = compare_images(img, ref);
    INFO("rel L1 " << e.rel_l1 << ", holes " << e.holes);
    CHECK(e.rel_l1 < 0.005);
    CHECK(e.holes == 0);
}

TEST_CASE("sonar touching a mesh: a wall right behind it changes nothing", "[stiff]") {
    SceneDesc bare = floor_scene(1.0, {0, 30, 0});
    SceneDesc touching = bare;
    ObjectDesc wall;
    wall.box_m = Vec3d{0.1, 4, 3};
    wall.position_m = {-0.05, 0, 1.5}; // its front face passes through the sonar's position
    touching.objects.push_back(wall);
    const PolarImage ref = floor_reference(bare, 16), img = render(touching);
    check_finite(img);
    const ImageError e = compare_images(img, ref);
    INFO("rel L1 " << e.rel_l1);
    CHECK(e.rel_l1 < 0.005);
}

TEST_CASE("zero-area and non-manifold triangles: degenerate ones add nothing", "[stiff]") {
    // A 1 x 1 m plate split in two triangles, plus degenerate triangles (repeated and collinear vertices)
    // and a fin of three triangles sharing one edge (non-manifold).
    const std::string clean =
        write_text("plate_clean.obj", "v -0.5 -0.5 0\nv 0.5 -0.5 0\nv 0.5 0.5 0\nv -0.5 0.5 0\n"
                                      "f 1 2 3\nf 1 3 4\n");
    const std::string dirty =
        write_text("plate_dirty.obj", "v -0.5 -0.5 0\nv 0.5 -0.5 0\nv 0.5 0.5 0\nv -0.5 0.5 0\nv 0 0 0\n"
                                      "v 0 0.2 0.3\nv 0 -0.2 0.3\nv 0.1 0 0.3\nv -0.5 -0.5 0\nv -0.1 0 0.3\n"
                                      "f 1 2 3\nf 1 3 4\nf 1 9 2\nf 1 5 3\n"
                                      "f 6 7 8\nf 6 7 10\nf 6 7 5\n");
    SceneDesc base = floor_scene(1.0, {0, 30, 0});
    base.seafloor.reset();
    ObjectDesc plate;
    plate.mesh = plate.mesh_resolved = clean;
    plate.position_m = {1.8, 0, 0.0};
    base.objects.push_back(plate);
    SceneDesc with_junk = base;
    with_junk.objects[0].mesh = with_junk.objects[0].mesh_resolved = dirty;
    // The fin hangs 0.3 m above the plate centre: compare only where it cannot be seen, i.e. check that the
    // degenerate triangles leave the plate's echo finite and close to the clean plate's outside the fin's
    // shadow.
    const PolarImage a = render(base), b = render(with_junk);
    check_finite(a);
    check_finite(b);
    long differing = 0, echoing = 0;
    for (size_t n = 0; n < a.level_db.size(); ++n) {
        echoing += a.level_db[n] > -INFINITY;
        differing += std::abs(a.level_db[n] - b.level_db[n]) > 0.01 && a.level_db[n] > -INFINITY;
    }
    INFO("bins differing " << differing << " of " << echoing);
    CHECK(echoing > 100);
    CHECK(differing < echoing / 5); // only the fin's own echo and shadow differ
}

TEST_CASE("1 beam, 1 elevation ray, and 100000 elevation rays", "[stiff]") {
    SceneDesc one = floor_scene(1.0, {0, 30, 0});
    one.sonar.beams = 1, one.sampling.elevation_rays = 1, set_scheme(one.sampling, SamplingScheme::Spread);
    {
        const PolarImage img = render(one), ref = floor_reference(one, 16);
        REQUIRE(check_finite(img) > 0);
        // One ray for the whole 32 x 14 deg aperture is a one-point quadrature: its total energy still
        // agrees.
        double e_img = 0, e_ref = 0;
        for (size_t n = 0; n < img.level_db.size(); ++n) {
            if (img.level_db[n] > -INFINITY) e_img += std::pow(10.0, (img.level_db[n] - 100) / 10);
            if (ref.level_db[n] > -INFINITY) e_ref += std::pow(10.0, (ref.level_db[n] - 100) / 10);
        }
        INFO("energy ratio " << e_img / e_ref);
        CHECK(e_img / e_ref == Approx(1.0).margin(0.5));
    }
    SceneDesc dense = floor_scene(1.0, {0, 30, 0}, SamplingScheme::Spread);
    dense.sonar.beams = 4, dense.sonar.azimuth_fov_deg = 1.0, dense.sampling.elevation_rays = 100000;
    const ImageError e = against_floor_reference(dense);
    CHECK(e.rel_l1 < 1e-4);
    CHECK(e.holes == 0);
}

TEST_CASE("a scene where nothing echoes gives an all -inf image", "[stiff]") {
    SceneDesc s = floor_scene(1.0, {0, -45, 0}); // looking up, the floor is behind and below the aperture
    const PolarImage img = render(s);
    CHECK(check_finite(img) == 0);
    SceneDesc empty;
    empty.objects.clear();
    empty.seafloor.reset();
    CHECK(check_finite(render(empty)) == 0);
}

TEST_CASE("kept rays under extreme slider values: the estimate made anew stays finite, the image too",
          "[stiff]") {
    // The viewer keeps a placement after a slider that steers the sampler (TraceControl::keep_placement):
    // from a floor at 1200 kHz to 10 MHz at -2 C (~55 dB/m, levels ~10^-50 apart), to a floor whose nu is at
    // its bound (-200 dB: the whole image 170 dB down), and to q = 100 (the echo in a sliver near normal).
    TraceControl keep;
    keep.keep_placement = true;
    const SceneDesc before = floor_scene(1.0, {0, 30, 0});
    SceneDesc absorbing = before, silent = before, sharp = before;
    absorbing.sonar.frequency_khz = 10000, absorbing.water.temperature_c = -2;
    silent.seafloor->material.nu_db = -200;
    sharp.seafloor->material.q = 100;
    for (const SceneDesc& after : {absorbing, silent, sharp}) {
        REQUIRE(changed_stage(before, after) == Stage::Place);
        Simulator sim(before);
        const auto first = sim.render(keep);
        REQUIRE(first->error_estimate.meets(before.sampling));
        const TraceResult::ErrorEstimate e = reestimate_error(first->hits(), after);
        INFO("estimated anew: rel L1 " << e.rel_l1 << ", median " << e.median_abs_db << " dB");
        REQUIRE(e.valid);
        CHECK(std::isfinite(e.rel_l1));
        CHECK(std::isfinite(e.median_abs_db));
        CHECK(std::isfinite(e.p95_abs_db));
        sim.set_scene(after);
        const auto f = sim.render(keep);
        CHECK(check_finite(f->polar()) > 0);
        // Kept only where the estimate made anew meets the tolerances (else traced anew, which meets them),
        // and then the image is within them of the floor's integral.
        CHECK(f->placement_kept == e.meets(after.sampling));
        CHECK(f->error_estimate.meets(after.sampling));
        const ImageError err = compare_images(f->ideal(), floor_reference(after, 4));
        CHECK(err.rel_l1 <= after.sampling.tolerance_rel_l1);
        CHECK(err.median_abs_db <= after.sampling.tolerance_db);
    }
}

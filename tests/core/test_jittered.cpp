// Jittered placement (sampling.scheme "jittered"): the same scene traces the same rays; a shading change
// re-shades and re-estimates without a ray; its error estimate (two independent halves and the footprint's
// bias) against the semi-analytic floor integral and a mesh scene's dense grid.
#include "floor_reference.hpp"
#include "support.hpp"

#include "core/analysis/reference.hpp"
#include "core/display/display_range.hpp"
#include "core/pipeline/simulator.hpp"
#include "core/scene/scene_io.hpp"
#include "core/scene/params.hpp"
#include "core/scene/sampling_scheme.hpp"
#include "core/base/errors.hpp"

#include <catch2/catch.hpp>
#include <cstdio>

using namespace sonarsim;
using namespace sonarsim::test;

namespace {

SceneDesc jittered_floor(int elevation_rays, int azimuth_rays = 1) {
    SceneDesc s; // paper defaults: 128 beams, 512 bins over [0.5, 5) m
    s.sonar.pose.position_m = {0.3, -0.2, 0.9};
    s.sonar.pose.orientation_deg = {0, 30, 25};
    s.seafloor = Seafloor{};
    set_scheme(s.sampling, SamplingScheme::Jittered);
    s.sampling.elevation_rays = elevation_rays, s.sampling.azimuth_rays = azimuth_rays;
    return s;
}

/// The floor with a 0.4 m cube on it: edges in elevation and azimuth, shadows.
SceneDesc jittered_cube(int elevation_rays, int azimuth_rays = 1) {
    SceneDesc s = jittered_floor(elevation_rays, azimuth_rays);
    ObjectDesc cube;
    cube.box_m = Vec3d{0.4, 0.4, 0.4};
    cube.position_m = {2.2, 0.6, 0.2};
    cube.orientation_deg = {0, 0, 20};
    s.objects.push_back(cube);
    return s;
}

/// Renders s and checks that its estimate lies within [low, 1.6] x its error against `ref`.
void check_estimate(const char* name, const SceneDesc& s, const std::vector<double>& ref, double low) {
    Simulator sim(s);
    const auto f = sim.render();
    const double err = relative_l1(echo_intensity(f->polar(), s.sonar.noise_level_db), ref);
    const auto& e = f->error_estimate;
    REQUIRE(e.valid);
    std::printf("jittered %s %d x %d: measured rel L1 %.4f %%, estimated %.4f %% (ratio %.2f)\n", name,
                s.sampling.elevation_rays, s.sampling.azimuth_rays, 100 * err, 100 * e.rel_l1,
                e.rel_l1 / err);
    CHECK(e.rel_l1 > low * err);
    CHECK(e.rel_l1 < 1.6 * err);
}

} // namespace

TEST_CASE("jittered: the same scene traces the same rays, four per stratum", "[jittered]") {
    const SceneDesc s = jittered_cube(41, 2);
    Simulator a(s), b(s);
    const auto fa = a.render(), fb = b.render();
    CHECK(fa->hits().rays_traced == std::uint64_t(4) * s.sonar.beams * 41 * 2);
    CHECK(fa->polar().level_db == fb->polar().level_db);
    REQUIRE(fa->error_estimate.valid);
    CHECK(fa->error_estimate.rel_l1 == fb->error_estimate.rel_l1);
    // Another pose gives other rays, and the halves are not copies of each other.
    CHECK(fa->error_estimate.variance_rel_l1 > 0);
}

TEST_CASE("jittered: a shading change re-shades and re-estimates without tracing a ray", "[jittered]") {
    SceneDesc s = jittered_cube(41);
    Simulator sim(s);
    const auto before = sim.render();
    const std::uint64_t rays = sim.rays_traced();
    s.objects[0].material = Material{-20.0, 1.5, 0.3, 20.0}; // a specular lobe on the cube
    s.sonar.source_level_db += 6;
    REQUIRE(changed_stage(sim.scene(), s) == Stage::Shade);
    sim.set_scene(s);
    const auto after = sim.render();
    CHECK(sim.rays_traced() == rays); // counted: no ray traced
    CHECK(after->polar().level_db != before->polar().level_db);
    // The placement does not depend on shading: a fresh simulator of the new scene makes the same bytes
    // and the same estimate.
    Simulator fresh(s);
    const auto f = fresh.render();
    CHECK(f->polar().level_db == after->polar().level_db);
    REQUIRE(after->error_estimate.valid);
    CHECK(after->error_estimate.rel_l1 == f->error_estimate.rel_l1);
    CHECK(after->error_estimate.rel_l1 != before->error_estimate.rel_l1);
}

TEST_CASE("jittered: the estimate tracks the floor's error against the semi-analytic integral",
          "[jittered][floor]") {
    for (int M : {25, 75}) {
        const SceneDesc s = jittered_floor(M);
        check_estimate("floor", s, floor_reference_intensity(s), 0.7);
    }
}

TEST_CASE("jittered: the estimate tracks a cube's error against a dense spread grid", "[jittered]") {
    SceneDesc dense = jittered_cube(3001, 9);
    set_scheme(dense.sampling, SamplingScheme::Spread);
    Simulator d(dense);
    const std::vector<double> ref = echo_intensity(d.render()->polar(), dense.sonar.noise_level_db);
    for (int M : {25, 75}) check_estimate("cube", jittered_cube(M), ref, 0.6);
}

TEST_CASE("jittered: point binning and paper normals are rejected with the key named", "[jittered]") {
    SceneDesc s = jittered_floor(11);
    s.sampling.binning = EchoBinning::Point;
    CHECK_THROWS_WITH(validate_scene(s, "x.json"), Catch::Contains("sampling.binning"));
    s = jittered_floor(11);
    s.sampling.normals = NormalSource::Paper;
    CHECK_THROWS_WITH(validate_scene(s, "x.json"), Catch::Contains("sampling.normals"));
}

TEST_CASE("jittered: a sonar moving during its frame keeps its halves and its estimate", "[jittered]") {
    SceneDesc s = jittered_cube(41);
    s.sonar.velocity_mps = {2.0, 0.0, 0.0};
    Simulator sim(s);
    const auto f = sim.render();
    REQUIRE(f->hits().halves);
    REQUIRE(f->error_estimate.valid);
    CHECK(f->error_estimate.rel_l1 > 0);
    CHECK(f->error_estimate.rel_l1 < 0.2);
}

TEST_CASE("a drag's preview at the screen's precision: a jittered grid sized from its own estimate, measured "
          "within it",
          "[jittered]") {
    // The wreck (adaptive, the default) dragged about: each preview asks for half a grey level of its display
    // range (55-110 dB: 0.108 dB). The simulator sizes its jittered grid from the last preview's estimate.
    SceneDesc s = load_scene(SONARSIM_ASSETS "/scenes/shipwreck.json");
    s.sonar.beams = 64, s.sonar.range_bins = 500;
    const double target = half_grey_level_db(s.display);
    Simulator sim(s);
    TraceControl control;
    control.preview = true, control.preview_median_db = target;
    control.preview_budget_ms = 0; // sized by precision alone, however slow the machine (sanitizers)
    std::shared_ptr<const Frame> f;
    std::vector<int> strata;
    for (int k = 0; k < 6; ++k) {
        s.sonar.pose.position_m[0] += 0.02; // a drag: every preview traces its own pose
        sim.set_scene(s);
        strata.push_back(sim.preview_strata());
        f = sim.render(control);
        REQUIRE(f->preview());
        REQUIRE(f->hits().halves);
        REQUIRE(f->error_estimate.valid);
    }
    INFO("strata: first " << strata.front() << ", last " << strata.back());
    // Sized to the target: estimated at most it, and not with more than half to spare.
    CHECK(f->error_estimate.median_abs_db <= target);
    CHECK(f->error_estimate.median_abs_db >= 0.45 * target);
    // Measured against a dense grid of the same pose: within the screen's precision, and the estimate tracks
    // it.
    SceneDesc dense = s;
    set_scheme(dense.sampling, SamplingScheme::Spread);
    dense.sampling.elevation_rays = 2187, dense.sampling.azimuth_rays = 9;
    Simulator ref(dense);
    const ImageError e = compare_images(f->ideal(), ref.render()->ideal());
    std::printf("screen preview: %d strata, estimated median %.4f dB, measured %.4f dB, target %.4f dB\n",
                strata.back(), f->error_estimate.median_abs_db, e.median_abs_db, target);
    CHECK(e.median_abs_db <= 1.25 * target);
    CHECK(f->error_estimate.median_abs_db == Approx(e.median_abs_db).epsilon(0.4));
    // The full-quality image after it is the adaptive sampler's, traced anew.
    const auto full = sim.render();
    CHECK_FALSE(full->preview());
    CHECK_FALSE(full->hits().halves);
}

TEST_CASE("a screen-precision preview grows no larger than its time allows", "[jittered]") {
    // A budget far below what the target needs: the grid shrinks to what fits and stays there.
    SceneDesc s = load_scene(SONARSIM_ASSETS "/scenes/shipwreck.json");
    s.sonar.beams = 64, s.sonar.range_bins = 500;
    Simulator sim(s);
    TraceControl control;
    control.preview = true, control.preview_median_db = 1e-4, control.preview_budget_ms = 1e-3;
    for (int k = 0; k < 3; ++k) {
        s.sonar.pose.position_m[0] += 0.02;
        sim.set_scene(s);
        const auto f = sim.render(control);
        CHECK(f->error_estimate.median_abs_db > control.preview_median_db); // says it is not there
    }
    CHECK(sim.preview_strata() == 8); // the fewest strata a preview takes
}

// The staged pipeline: a change re-runs only the stages it affects, and the result equals a fresh render.
#include "core/analysis/reference.hpp"
#include "core/scene/scene_io.hpp"
#include "core/scene/sampling_scheme.hpp"
#include "core/pipeline/simulator.hpp"
#include "core/pipeline/memory_report.hpp"
#include "core/base/scratch_pool.hpp"
#include "core/display/sector.hpp"

#include <algorithm>
#include <atomic>
#include <catch2/catch.hpp>
#include <functional>
#include <string>

using namespace sonarsim;

TEST_CASE("incremental re-render equals a fresh render and starts at the right stage", "[simulator]") {
    struct Change {
        std::string what;
        std::function<void(SceneDesc&)> apply;
        Stage stage;
    };
    const Change changes[] = {
        {"display range", [](SceneDesc& s) { s.display.lo_db = 60; }, Stage::Display},
        {"colour map", [](SceneDesc& s) { s.display.colormap = Colormap::Viridis; }, Stage::Display},
        {"source level", [](SceneDesc& s) { s.sonar.source_level_db = 220; }, Stage::Shade},
        {"temperature", [](SceneDesc& s) { s.water.temperature_c = 20; },
         Stage::Place}, // adaptive: see below
        {"floor material", [](SceneDesc& s) { s.seafloor->material.nu_db = -30; }, Stage::Place}, // adaptive
        {"object material", [](SceneDesc& s) { s.objects[0].material.nu_db = -40; }, Stage::Place},
        {"object specular lobe", [](SceneDesc& s) { s.objects[0].material.mu = 0.5; }, Stage::Place},
        {"pose", [](SceneDesc& s) { s.sonar.pose.orientation_deg[2] = -35; }, Stage::Trace},
        {"range window", [](SceneDesc& s) { s.sonar.range_max_m = 3; }, Stage::Trace},
        {"floor height", [](SceneDesc& s) { s.seafloor->height_m = -0.1; }, Stage::Trace},
        {"no floor", [](SceneDesc& s) { s.seafloor.reset(); }, Stage::Trace},
        {"object position", [](SceneDesc& s) { s.objects[0].position_m[0] = 1.45; }, Stage::Geometry},
        {"object turned and scaled", // in place: new instance transform
         [](SceneDesc& s) {
             s.objects[0].orientation_deg = {10, -5, 30}, s.objects[0].scale = {1.5, 1, 0.8};
         },
         Stage::Geometry},
        {"object shape", [](SceneDesc& s) { (*s.objects[0].box_m)[1] *= 1.5; },
         Stage::Geometry}, // new geometry
        {"nothing", [](SceneDesc&) {}, Stage::None},
    };
    for (const Change& c : changes) {
        INFO(c.what);
        const SceneDesc before = default_scene();
        SceneDesc after = before;
        c.apply(after);
        CHECK(changed_stage(before, after) == c.stage);
        Simulator sim(before);
        sim.render();
        sim.set_scene(after);
        CHECK(sim.pending() == (c.stage == Stage::Geometry ? Stage::Trace : c.stage));
        const auto inc = sim.render();
        CHECK(sim.pending() == Stage::None);
        Simulator fresh(after);
        const auto ref = fresh.render();
        CHECK(inc->polar().level_db == ref->polar().level_db);
        CHECK(inc->sector().pixels == ref->sector().pixels);
        CHECK(inc->hits().rays_traced == ref->hits().rays_traced);
    }
}

TEST_CASE("uniform and spread schemes re-shade on absorption and material changes", "[simulator]") {
    for (SamplingScheme scheme : {SamplingScheme::Uniform, SamplingScheme::Spread}) {
        SceneDesc before = default_scene();
        set_scheme(before.sampling, scheme);
        SceneDesc after = before;
        after.water.temperature_c = 20;
        after.objects[0].material.mu = 0.5;
        after.seafloor->material.nu_db = -30;
        CHECK(changed_stage(before, after) == Stage::Shade);
        Simulator sim(before);
        sim.render();
        sim.set_scene(after);
        const auto inc = sim.render();
        Simulator fresh(after);
        CHECK(inc->polar().level_db == fresh.render()->polar().level_db);
    }
}

TEST_CASE("a material edit re-traces a full image under the adaptive scheme and re-shades otherwise",
          "[simulator]") {
    // The adaptive sampler places its rays by the materials' levels: the re-render equals a fresh render
    // only if it re-traces. apply_setting, changed_stage and the Simulator give the same answer.
    for (SamplingScheme scheme :
         {SamplingScheme::Adaptive, SamplingScheme::Uniform, SamplingScheme::Spread}) {
        const Stage expected = scheme == SamplingScheme::Adaptive ? Stage::Place : Stage::Shade;
        SceneDesc before = default_scene();
        set_scheme(before.sampling, scheme);
        SceneDesc after = before;
        CHECK(apply_setting(after, "seafloor.material.nu_db", -30.0, "test") == expected);
        CHECK(changed_stage(before, after) == expected);
        Simulator sim(before);
        const auto first = sim.render();
        sim.set_scene(after);
        CHECK(sim.pending() == expected);
        const auto inc = sim.render();
        CHECK((inc->hits_ptr == first->hits_ptr) == (expected == Stage::Shade));
        Simulator fresh(after);
        const auto ref = fresh.render();
        CHECK(inc->polar().level_db == ref->polar().level_db);
        CHECK(inc->sector().pixels == ref->sector().pixels);
    }
}

TEST_CASE("frames share the stages a change leaves alone", "[simulator]") {
    SceneDesc s = default_scene();
    Simulator sim(s);
    const auto first = sim.render();
    const std::vector<std::uint8_t> first_pixels = first->sector().pixels;

    s.display.lo_db = 70; // display only: the same trace and polar image, a new fan
    sim.set_scene(s);
    const auto display = sim.render();
    CHECK(display->hits_ptr == first->hits_ptr);
    CHECK(display->polar_ptr == first->polar_ptr);
    CHECK(display->sector_ptr != first->sector_ptr);
    CHECK(first->sector().pixels == first_pixels); // a finished frame never changes

    s.sonar.source_level_db = 225; // re-shade: the same trace
    sim.set_scene(s);
    const auto shaded = sim.render();
    CHECK(shaded->hits_ptr == first->hits_ptr);
    CHECK(shaded->polar_ptr != first->polar_ptr);

    const auto again = sim.render(); // nothing stale: everything shared
    CHECK(again->hits_ptr == shaded->hits_ptr);
    CHECK(again->polar_ptr == shaded->polar_ptr);
    CHECK(again->sector_ptr == shaded->sector_ptr);
}

TEST_CASE("a fan height re-forms the fan only, at that height", "[simulator]") {
    SceneDesc s = default_scene(); // 512 bins: the default fan is 512 px high
    Simulator sim(s);
    const auto full = sim.render();
    REQUIRE(full->sector().height == 512);
    sim.set_fan_height_px(256);
    CHECK(sim.pending() == Stage::Display);
    const auto small = sim.render();
    CHECK(small->hits_ptr == full->hits_ptr);
    CHECK(small->polar_ptr == full->polar_ptr);
    CHECK(small->sector().height == 256);
    CHECK(small->sector().width == SectorLayout(s.sonar, 256).width());
    CHECK(small->sector_map_ptr->layout().height() == 256);
    // The same pixels as the fan formed at that height from the same image.
    CHECK(small->sector().pixels ==
          SectorResampler(s.sonar, 256).apply(small->polar(), small->display).pixels);
    sim.set_fan_height_px(256); // unchanged: nothing stale
    CHECK(sim.pending() == Stage::None);
    sim.set_fan_height_px(0);
    const auto back = sim.render();
    CHECK(back->sector().pixels == full->sector().pixels);
    CHECK_THROWS_AS(sim.set_fan_height_px(-1), std::invalid_argument);
}

TEST_CASE("a cancelled render leaves the simulator consistent", "[simulator]") {
    SceneDesc s = default_scene();
    Simulator sim(s);
    const auto before = sim.render();
    s.sonar.pose.orientation_deg[2] = -30;
    sim.set_scene(s);
    const std::atomic<bool> cancel{true};
    TraceControl control;
    control.cancel = &cancel;
    CHECK_THROWS_AS(sim.render(control), TraceCancelled);
    CHECK(sim.pending() == Stage::Trace); // still stale
    const auto after = sim.render();
    CHECK(after->hits_ptr != before->hits_ptr);
    Simulator fresh(s);
    CHECK(after->polar().level_db == fresh.render()->polar().level_db);
}

TEST_CASE("a preview is never taken for the full image", "[simulator]") {
    SceneDesc s = default_scene();
    Simulator sim(s);
    TraceControl preview;
    preview.preview = true;
    const auto coarse = sim.render(preview);
    REQUIRE(coarse->preview());
    CHECK_FALSE(coarse->hits().error_estimate.valid);
    const auto coarse_again = sim.render(preview); // a preview of an unchanged scene is reused
    CHECK(coarse_again->hits_ptr == coarse->hits_ptr);
    const auto full = sim.render(); // same scene, but the full image was never made: re-trace
    CHECK_FALSE(full->preview());
    CHECK(full->hits().rays_traced > coarse->hits().rays_traced);
    Simulator fresh(s);
    CHECK(full->polar().level_db == fresh.render()->polar().level_db);
    const auto full_again = sim.render(preview); // the full image is better than a preview: keep it
    CHECK(full_again->hits_ptr == full->hits_ptr);
}

TEST_CASE("a preview after a shading-only change re-shades the hits it has and traces no ray",
          "[simulator]") {
    // The viewer's sliders: frequency, temperature, depth and every material value steer the adaptive
    // sampler (Stage::Place), the source level does not (Stage::Shade). Either way a preview traces nothing;
    // the full image that follows re-traces only where the placement was steered, and equals a fresh render.
    struct Change {
        std::string what;
        std::function<void(SceneDesc&)> apply;
        Stage stage;
    };
    const Change changes[] = {
        {"floor nu", [](SceneDesc& s) { s.seafloor->material.nu_db = -20; }, Stage::Place},
        {"object q", [](SceneDesc& s) { s.objects[0].material.q = 4; }, Stage::Place},
        {"temperature", [](SceneDesc& s) { s.water.temperature_c = 25; }, Stage::Place},
        {"depth", [](SceneDesc& s) { s.water.depth_m = 500; }, Stage::Place},
        {"frequency", [](SceneDesc& s) { s.sonar.frequency_khz = 1500; }, Stage::Place},
        {"source level", [](SceneDesc& s) { s.sonar.source_level_db = 215; }, Stage::Shade},
    };
    TraceControl preview;
    preview.preview = true;
    for (const Change& c : changes) {
        INFO(c.what);
        const SceneDesc before = default_scene();
        REQUIRE(scheme_of(before.sampling) == SamplingScheme::Adaptive);
        SceneDesc after = before;
        c.apply(after);
        REQUIRE(changed_stage(before, after) == c.stage);
        Simulator sim(before);
        const auto full = sim.render();
        const std::uint64_t rays = sim.rays_traced();
        CHECK(rays == full->hits().rays_traced + full->hits().multipath_rays);
        sim.set_scene(after);
        const auto shaded = sim.render(preview);
        CHECK(sim.rays_traced() == rays); // counted: no ray traced
        CHECK(shaded->hits_ptr == full->hits_ptr);
        CHECK(shaded->ideal().level_db != full->ideal().level_db);
        CHECK(shaded->preview() == (c.stage == Stage::Place)); // its placement is an earlier scene's
        // The kept rays shade the new scene within the sampler's tolerances of what its own rays give.
        Simulator fresh(after);
        const auto ref = fresh.render();
        const ImageError e = compare_images(shaded->ideal(), ref->ideal());
        CHECK(e.rel_l1 <= after.sampling.tolerance_rel_l1);
        CHECK(e.median_abs_db <= after.sampling.tolerance_db);
        const auto settled = sim.render(); // the full image: re-traced only if the placement was steered
        CHECK((sim.rays_traced() > rays) == (c.stage == Stage::Place));
        CHECK_FALSE(settled->preview());
        CHECK(settled->polar().level_db == ref->polar().level_db);
        CHECK(settled->sector().pixels == ref->sector().pixels);
    }
}

TEST_CASE("a frame's fan goes back to the scratch pool, and a kept buffer is written over in full",
          "[simulator]") {
    SceneDesc s = default_scene();
    Simulator sim(s);
    const size_t n = size_t(SectorLayout(s.sonar, 0).width()) * size_t(SectorLayout(s.sonar, 0).height()) * 3;
    // Empty the pool of byte buffers (it keeps at most kScratchPoolBuffers), then fill it with poisoned ones.
    std::vector<std::vector<std::uint8_t>> drained;
    for (int i = 0; i < scratch::kScratchPoolBuffers; ++i) drained.push_back(scratch::take<std::uint8_t>(n));
    for (auto& v : drained) std::fill(v.begin(), v.end(), std::uint8_t(0xAB)), scratch::give(std::move(v));

    auto first = sim.render(); // formed in a poisoned buffer
    const auto fresh = SectorResampler(s.sonar, 0).apply(first->polar(), first->display);
    CHECK(first->sector().width == fresh.width);
    CHECK(first->sector().height == fresh.height);
    CHECK((first->sector().pixels == fresh.pixels)); // no byte left from the buffer's last use

    // Dropped by its last holder, the fan's buffer is the pool's again.
    drained.clear();
    for (int i = 0; i < scratch::kScratchPoolBuffers; ++i) drained.push_back(scratch::take<std::uint8_t>(n));
    const std::uint8_t* const pixels = first->sector().pixels.data();
    s.sonar.pose.orientation_deg[2] += 1;
    sim.set_scene(s);
    const auto second = sim.render(); // the simulator holds the second frame only, `first` its own
    CHECK(scratch::take<std::uint8_t>(n).data() != pixels);
    first.reset();
    CHECK(scratch::take<std::uint8_t>(n).data() == pixels);
    CHECK(second->sector().pixels.data() != pixels);
}

TEST_CASE("the scratch pool keeps at most its byte budget and reports what it keeps", "[simulator]") {
    // Empty the pool: buffers taken out and dropped are freed, not given back.
    for (int i = 0; i < 3 * scratch::kScratchPoolBuffers && scratch::kept_bytes() > 0; ++i)
        (void)scratch::take<double>(0), (void)scratch::take<float>(0), (void)scratch::take<std::uint8_t>(0);
    REQUIRE(scratch::kept_bytes() == 0);
    // Capacity counts, not size: reserved and never touched, so the test maps no memory.
    const std::size_t half = scratch::kScratchPoolMaxBytes / 2;
    std::vector<std::uint8_t> bytes;
    bytes.reserve(half);
    scratch::give(std::move(bytes));
    CHECK(scratch::kept_bytes() == half);
    std::vector<float> floats;
    floats.reserve(half / sizeof(float));
    scratch::give(std::move(floats));
    CHECK(scratch::kept_bytes() == 2 * half); // exactly the budget
    std::vector<double> one(1);
    scratch::give(std::move(one)); // past the budget: freed
    CHECK(scratch::kept_bytes() == 2 * half);
    // Taken out again, the bytes are no longer the pool's.
    (void)scratch::take<std::uint8_t>(16);
    CHECK(scratch::kept_bytes() == half);
    const MemoryReport m = memory_report();
    CHECK(m.kept_bytes == half);
    CHECK(m.kept_budget_bytes == scratch::kScratchPoolMaxBytes);
    CHECK(to_string(m).find("kept buffers 256 of 512 MiB") != std::string::npos);
}

TEST_CASE("a change of the elevation aperture alone keeps the fan's resampling taps", "[simulator]") {
    SceneDesc s;
    s.sampling.elevation_rays = 21;
    Simulator sim(s);
    const auto a = sim.render();
    s.sonar.elevation_fov_deg = 10;
    sim.set_scene(s);
    const auto b = sim.render();
    CHECK(a->grid_ptr != b->grid_ptr); // the grid holds the aperture
    CHECK(b->grid().elevation_half_deg() == 5);
    CHECK(a->sector_map_ptr == b->sector_map_ptr);
}

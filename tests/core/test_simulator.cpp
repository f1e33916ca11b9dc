// The staged pipeline: a change re-runs only the stages it affects, and the result equals a fresh render.
#include "core/scene_io.hpp"
#include "core/simulator.hpp"

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
         Stage::Trace}, // adaptive: see below
        {"floor material", [](SceneDesc& s) { s.seafloor->material.nu_db = -30; }, Stage::Trace}, // adaptive
        {"object material", [](SceneDesc& s) { s.objects[0].material.nu_db = -40; }, Stage::Trace},
        {"object specular lobe", [](SceneDesc& s) { s.objects[0].material.mu = 0.5; }, Stage::Trace},
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
        const Frame& inc = sim.render();
        CHECK(sim.pending() == Stage::None);
        Simulator fresh(after);
        const Frame& ref = fresh.render();
        CHECK(inc.polar.level_db == ref.polar.level_db);
        CHECK(inc.sector.pixels == ref.sector.pixels);
        CHECK(inc.hits.rays_traced == ref.hits.rays_traced);
    }
}

TEST_CASE("uniform and spread schemes re-shade on absorption and material changes", "[simulator]") {
    for (SamplingScheme scheme : {SamplingScheme::Uniform, SamplingScheme::Spread}) {
        SceneDesc before = default_scene();
        before.sampling.scheme = scheme;
        SceneDesc after = before;
        after.water.temperature_c = 20;
        after.objects[0].material.mu = 0.5;
        after.seafloor->material.nu_db = -30;
        CHECK(changed_stage(before, after) == Stage::Shade);
        Simulator sim(before);
        sim.render();
        sim.set_scene(after);
        const Frame& inc = sim.render();
        Simulator fresh(after);
        CHECK(inc.polar.level_db == fresh.render().polar.level_db);
    }
}

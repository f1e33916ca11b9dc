// Scene files: the shipped Fig. 9 scene, JSON round trips, --set assignments and a few bad inputs.
// (The exhaustive bad-input corpus lives elsewhere.)
#include "support.hpp"

#include "core/base/errors.hpp"
#include "core/scene/params.hpp"
#include "core/scene/sampling_scheme.hpp"
#include "core/scene/scene_io.hpp"

#include <catch2/catch.hpp>
#include <string>

using namespace sonarsim;

namespace {

/// Runs `f`, requires an InputError and returns it.
template <class F> InputError input_error(F&& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e;
    }
    FAIL("no InputError thrown");
    return InputError("", "", "");
}

} // namespace

TEST_CASE("assets/scenes/fig9.json is the built-in default scene", "[scene]") {
    const SceneDesc file = load_scene(SONARSIM_ASSETS "/scenes/fig9.json");
    const SceneDesc def = default_scene();
    CHECK(scene_to_json(file).dump(2) == scene_to_json(def).dump(2));
    // And the default scene is the paper's Fig. 9: pose 1 and the 70 x 120 x 220 mm prism on the floor.
    CHECK(def.sonar.pose.position_m == Vec3d{0.34, 2.42, 0.90});
    CHECK(def.sonar.pose.orientation_deg == Vec3d{-0.97, 29.79, -38.96});
    REQUIRE(def.objects.size() == 1);
    CHECK(*def.objects[0].box_m == Vec3d{0.07, 0.12, 0.22});
    CHECK(def.objects[0].position_m == Vec3d{1.5, 1.5, 0.11});
    REQUIRE(def.seafloor);
    CHECK(def.seafloor->height_m == 0.0);
    CHECK(def.sonar.beams == 128);
    CHECK(def.sampling.elevation_rays == 101);
}

TEST_CASE("fig9_pose2.json differs from the default only in the pose, kFig9Pose2", "[scene]") {
    SceneDesc p2 = load_scene(SONARSIM_ASSETS "/scenes/fig9_pose2.json");
    CHECK(p2.sonar.pose.position_m == kFig9Pose2.position_m);
    CHECK(p2.sonar.pose.orientation_deg == kFig9Pose2.orientation_deg);
    CHECK(kFig9Pose2.position_m != default_scene().sonar.pose.position_m);
    p2.sonar.pose = default_scene().sonar.pose;
    CHECK(scene_to_json(p2).dump() == scene_to_json(default_scene()).dump());
}

TEST_CASE("scene_to_json -> parse_scene round trip", "[scene]") {
    SceneDesc s = default_scene();
    s.sonar.pose.position_m = {1.25, -3.5, 2.0};
    s.sonar.range_bins = 300, s.sonar.beams = 96, s.sonar.range_max_m = 7.5;
    s.sampling.elevation_rays = 123, s.sampling.azimuth_rays = 3;
    set_scheme(s.sampling, SamplingScheme::Uniform), s.sampling.normals = NormalSource::Paper;
    s.water.temperature_c = 4.5;
    s.seafloor->material.mu = 0.25, s.seafloor->material.h_deg = 7.0;
    ObjectDesc mesh;
    mesh.mesh = mesh.mesh_resolved = test::out_path("roundtrip_dummy.obj");
    mesh.position_m = {0.1, 0.2, 0.3}, mesh.orientation_deg = {10, 20, 30}, mesh.scale = {1, 2, 3};
    mesh.material.nu_db = -30, mesh.material.q = 1.5;
    s.objects.push_back(mesh);

    const json j = scene_to_json(s);
    const SceneDesc back = parse_scene(j.dump(), "roundtrip.json", "/nonexistent");
    CHECK(scene_to_json(back).dump(2) == j.dump(2));
    CHECK(scheme_of(back.sampling) == SamplingScheme::Uniform);
    CHECK(back.sampling.normals == NormalSource::Paper);
    REQUIRE(back.objects.size() == 2);
    CHECK(back.objects[1].mesh_resolved == mesh.mesh_resolved); // absolute path stays as it is
    CHECK(back.objects[1].scale == Vec3d{1, 2, 3});

    // No seafloor key: no floor; and that, too, round-trips.
    s.seafloor.reset();
    const SceneDesc nofloor = parse_scene(scene_to_json(s).dump(), "nofloor.json", "/");
    CHECK_FALSE(nofloor.seafloor);
    CHECK(scene_to_json(nofloor).dump() == scene_to_json(s).dump());
}

TEST_CASE("missing keys take the paper's defaults and mesh paths resolve against the scene's folder",
          "[scene]") {
    const SceneDesc s = parse_scene(R"({"sonar": {"beams": 64}, "objects": [{"mesh": "m/x.obj"}]})", "a.json",
                                    "/data/scenes");
    CHECK(s.sonar.beams == 64);
    CHECK(s.sonar.range_max_m == 5.0);
    CHECK(s.sonar.frequency_khz == 3000.0);
    CHECK(s.sampling.elevation_rays == 101);
    CHECK_FALSE(s.seafloor); // no seafloor key
    REQUIRE(s.objects.size() == 1);
    CHECK(s.objects[0].mesh_resolved == "/data/scenes/m/x.obj");
}

TEST_CASE("apply_setting_text applies key.path=value", "[scene]") {
    SceneDesc s = default_scene();
    CHECK(apply_setting_text(s, "sonar.range_max_m=8", "--set") == Stage::Trace);
    CHECK(s.sonar.range_max_m == 8.0);
    CHECK(apply_setting_text(s, "sampling.normals=paper", "--set") == Stage::Trace); // bare enum word
    CHECK(s.sampling.normals == NormalSource::Paper);
    CHECK(apply_setting_text(s, "sonar.position=[1,2,3]", "--set") == Stage::Trace);
    CHECK(s.sonar.pose.position_m == Vec3d{1, 2, 3});
    // What a material edit recomputes depends on the sampling scheme: test_simulator.cpp.
    apply_setting_text(s, "seafloor.material.nu_db=-30", "--set");
    CHECK(s.seafloor->material.nu_db == -30.0);
    apply_setting_text(s, "objects.0.material.q=3", "--set");
    CHECK(s.objects[0].material.q == 3.0);
    CHECK(apply_setting_text(s, "display.hi_db=150", "--set") == Stage::Display);
    CHECK(s.display.hi_db == 150.0);
}

TEST_CASE("bad inputs throw InputError naming the key", "[scene]") {
    SceneDesc s = default_scene();
    InputError e = input_error([&] { apply_setting_text(s, "sonar.range_maxx=8", "--set"); });
    CHECK(e.key() == "sonar.range_maxx");
    CHECK_THAT(e.what(), Catch::Contains("sonar.range_maxx"));

    e = input_error([&] { apply_setting_text(s, "sonar.beams=0", "--set"); });
    CHECK(e.key() == "sonar.beams");
    CHECK_THAT(e.what(), Catch::Contains("sonar.beams") && Catch::Contains("allowed"));

    e = input_error([&] { parse_scene(R"({"sonar": {"beams": "many"}})", "bad.json", "/"); });
    CHECK(e.file() == "bad.json");
    CHECK(e.key() == "sonar.beams");

    e = input_error(
        [&] { parse_scene(R"({"sonar": {"range_min_m": 3, "range_max_m": 2}})", "bad.json", "/"); });
    CHECK_THAT(e.what(), Catch::Contains("range_min_m"));

    e = input_error([&] { parse_scene(R"({"seafloor": {"material": {"nu": -40}}})", "bad.json", "/"); });
    CHECK(e.key() == "seafloor.material.nu");

    e = input_error([&] { parse_scene(R"({"objects": [{"box": [1, 1, 0]}]})", "bad.json", "/"); });
    CHECK_THAT(e.key(), Catch::StartsWith("objects[0].box"));

    e = input_error([&] { parse_scene(R"({"sampling": {"scheme": "fancy"}})", "bad.json", "/"); });
    CHECK(e.key() == "sampling.scheme");
    CHECK_THAT(e.what(), Catch::Contains("uniform") && Catch::Contains("spread"));

    e = input_error([&] { load_scene(test::out_path("no_such_scene.json")); });
    CHECK_THAT(e.what(), Catch::Contains("no_such_scene.json"));
}

TEST_CASE("sampling.placement and sampling.binning: the schemes name their combinations", "[scene]") {
    const std::pair<const char*, std::pair<const char*, const char*>> named[] = {
        {"uniform", {"grid", "point"}},
        {"spread", {"grid", "footprint"}},
        {"adaptive", {"adaptive", "footprint"}}};
    for (const auto& [scheme, settings] : named) {
        INFO(scheme);
        const std::string by_name = std::string(R"({"sampling": {"scheme": ")") + scheme + R"("}})";
        const std::string by_settings = std::string(R"({"sampling": {"placement": ")") + settings.first +
                                        R"(", "binning": ")" + settings.second + R"("}})";
        const SceneDesc a = parse_scene(by_name, "name.json", "/"),
                        b = parse_scene(by_settings, "two.json", "/");
        CHECK(scene_to_json(a) == scene_to_json(b));
        CHECK(a.sampling.placement == b.sampling.placement);
        CHECK(a.sampling.binning == b.sampling.binning);
        // Written as the scheme's name only, so that existing scenes' metadata stays as it was.
        const json j = scene_to_json(b)["sampling"];
        CHECK(j["scheme"] == scheme);
        CHECK_FALSE(j.contains("placement"));
        CHECK_FALSE(j.contains("binning"));
    }
    // --set either form, applied in order: the scheme sets both, a setting changes one.
    SceneDesc s = default_scene();
    apply_setting_text(s, "sampling.placement=grid", "--set");
    CHECK(scheme_of(s.sampling) == SamplingScheme::Spread);
    apply_setting_text(s, "sampling.binning=point", "--set");
    CHECK(scheme_of(s.sampling) == SamplingScheme::Uniform);
    apply_setting_text(s, "sampling.scheme=adaptive", "--set");
    CHECK(s.sampling.placement == RayPlacement::Adaptive);
    CHECK(s.sampling.binning == EchoBinning::Footprint);
    // Adaptive placement with point binning has no name and is rejected with one message.
    const InputError e =
        input_error([] { parse_scene(R"({"sampling": {"binning": "point"}})", "adaptive_point.json", "/"); });
    CHECK(std::string(e.what()).find("sampling.binning: adaptive placement needs \"footprint\" binning") !=
          std::string::npos);
    CHECK(find_param("sampling.placement") != nullptr);
    CHECK_THROWS_AS(apply_setting_text(s, "sampling.placement=random", "--set"), InputError);
}

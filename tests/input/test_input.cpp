// Bad input, in process: messages, key paths, limits, nothing clamped; every mesh of the corpus.
// (The same corpus also runs through the real binary: cases.txt.)
#include "core/base/errors.hpp"
#include "core/geometry/mesh.hpp"
#include "core/geometry/mesh_cache.hpp"
#include "core/scene/params.hpp"
#include "core/scene/scene_io.hpp"

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>

using namespace sonarsim;
namespace fs = std::filesystem;

namespace {

/// The message of the InputError that `f` throws ("" if it throws none).
template <class F> std::string error_of(F&& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

std::string write_temp(const std::string& name, const std::string& bytes) {
    const fs::path dir = fs::temp_directory_path() / "sonarsim_test_input";
    fs::create_directories(dir);
    const fs::path p = dir / name;
    std::ofstream(p, std::ios::binary) << bytes;
    return p.string();
}

} // namespace

TEST_CASE("an InputError is one line: control characters are escaped", "[input]") {
    const InputError e("a\nb.json", "sonar.\tkey", "bad\r\x1b[31m value");
    CHECK(std::string(e.what()) == "a\\nb.json: sonar.\\tkey: bad\\r\\x1b[31m value");
    CHECK(e.file() == "a\nb.json"); // the parts stay as given
}

TEST_CASE("JSON errors name the file and the line", "[input]") {
    CHECK(error_of([] {
              parse_scene("{\n\"sonar\": {\n\"beams\": 3,\n}\n}", "s.json", ".");
          }).rfind("s.json:4: invalid JSON", 0) == 0);
    CHECK(error_of([] {
              parse_scene("{\"sonar\":\n{\"beams\": -1e999}}", "s.json", ".");
          }).rfind("s.json:2: invalid JSON: number overflow", 0) == 0);
    CHECK(error_of([] { parse_scene("", "s.json", "."); }).rfind("s.json:1: invalid JSON", 0) == 0);
    CHECK(error_of([] { parse_scene("7", "s.json", "."); }) == "s.json: the top level must be a JSON object");
}

TEST_CASE("duplicate keys are errors that name the key path", "[input]") {
    const std::string text = R"({"objects": [{"box": [1, 1, 1]},
                                             {"box": [1, 1, 1], "material": {"q": 1, "q": 2}}]})";
    CHECK(error_of([&] { parse_scene(text, "s.json", "."); }) ==
          "s.json: objects[1].material.q: duplicate key; each key may appear once per object");
    CHECK(error_of([] {
              parse_scene(R"({"water": {}, "water": {}})", "s.json", ".");
          }).find("s.json: water: duplicate key") == 0);
}

TEST_CASE("nesting is limited", "[input]") {
    const std::string deep = std::string(100000, '[') + std::string(100000, ']');
    CHECK(error_of([&] { parse_scene(deep, "s.json", "."); }).find("nesting deeper than 32 levels") !=
          std::string::npos);
}

TEST_CASE("a rejected value leaves the scene as it was (nothing clamped)", "[input]") {
    SceneDesc s = default_scene();
    const SceneDesc before = s;
    for (const char* bad :
         {"sonar.beams=0", "sonar.beams=1e9", "sonar.azimuth_fov_deg=180", "sonar.range_max_m=-5",
          "water.temperature_c=99", "seafloor.material.q=-1", "objects.0.material.h_deg=0",
          "sonar.position=[0,0,1e7]", "sampling.scheme=best"}) {
        INFO(bad);
        CHECK_FALSE(error_of([&] { apply_setting_text(s, bad, "--set"); }).empty());
        CHECK(scene_to_json(s) == scene_to_json(before));
    }
}

TEST_CASE("buffer limits: rays, image cells, sector pixels, bin width", "[input]") {
    SceneDesc s = default_scene();
    s.sonar.beams = 4096, s.sonar.range_bins = 16384; // exactly kMaxImageCells
    s.sampling.elevation_rays = 1;
    CHECK(error_of([&] { validate_scene(s, "x"); }).empty());
    s.sonar.range_bins = 16385;
    CHECK(error_of([&] { validate_scene(s, "x"); }).find("cells per image") != std::string::npos);

    s = default_scene();
    s.sonar.beams = 100, s.sampling.azimuth_rays = 1000, s.sampling.elevation_rays = 501;
    CHECK(error_of([&] { validate_scene(s, "x"); }).find("rays per image") != std::string::npos);

    s = default_scene();
    CHECK(sector_image_pixels(s.sonar) < 1e6);
    s.sonar.range_max_m = 1000, s.sonar.range_min_m = 999.999, s.sonar.range_bins = 1;
    s.sonar.azimuth_fov_deg = 0.162;
    CHECK(sector_image_pixels(s.sonar) > kMaxImageCells);
    CHECK(error_of([&] { validate_scene(s, "x"); }).find("sector image") != std::string::npos);

    s = default_scene();
    s.sonar.range_min_m = 0, s.sonar.range_max_m = 5e-324; // a denormal window
    CHECK(error_of([&] { validate_scene(s, "x"); }).find("below the minimum") != std::string::npos);
}

TEST_CASE("the example scenes round-trip through scene_to_json", "[input]") {
    for (const auto& e : fs::directory_iterator(fs::path(SONARSIM_INPUT_DIR) / "../../assets/scenes")) {
        INFO(e.path().string());
        const SceneDesc s = load_scene(e.path().string());
        const json j = scene_to_json(s);
        CHECK(scene_to_json(parse_scene(j.dump(), "again.json", "/")) == j);
    }
}

TEST_CASE("every bad mesh of the corpus is rejected with a message naming it", "[input][mesh]") {
    int n = 0;
    for (const auto& e : fs::directory_iterator(fs::path(SONARSIM_INPUT_DIR) / "meshes")) {
        const std::string name = e.path().filename().string();
        if (name == "ok.obj" || name == "big_coords.obj") continue;
        INFO(name);
        const std::string msg = error_of([&] { load_mesh(e.path().string(), "s.json", "objects[0].mesh"); });
        CHECK(msg.rfind("s.json: objects[0].mesh: mesh \"" + e.path().string() + "\"", 0) == 0);
        CHECK(msg.find('\n') == std::string::npos);
        ++n;
    }
    CHECK(n >= 40);
    const TriMesh ok = load_mesh(std::string(SONARSIM_INPUT_DIR) + "/meshes/ok.obj", "s.json", "m");
    CHECK(ok.vertices.size() == 4);
    CHECK(ok.triangles.size() == 4);
}

TEST_CASE("zero-area faces are skipped, a mesh of nothing else has no faces", "[input][mesh]") {
    const std::string v = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    const TriMesh m = load_mesh(write_temp("degenerate_one.obj", v + "f 1 2 3\nf 1 1 2\n"), "s", "k");
    CHECK(m.triangles.size() == 1);
    // A face written with fewer than 3 corners is malformed, not merely degenerate (OpenMesh aborts on some).
    CHECK(error_of([&] {
              load_mesh(write_temp("two_corners.obj", v + "f 1 2 3\nf 2 3\n"), "s", "k");
          }).find("line 5: a face needs at least 3 corners") != std::string::npos);
    CHECK(error_of([&] {
              load_mesh(write_temp("degenerate_all.obj", v + "f 1 1 2\n"), "s", "k");
          }).find("contains no faces") != std::string::npos);
    CHECK(error_of([&] {
              load_mesh(write_temp("degenerate.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 0 1\n"), "s", "k");
          }).find("contains no faces") != std::string::npos);
}

TEST_CASE("OFF: comments, counts on the first line, colours", "[input][mesh]") {
    const TriMesh m =
        load_mesh(write_temp("comments.off", "COFF 4 2 0 # tetra\n# vertices\n0 0 0 255 0 0 255\n"
                                             "1 0 0 255 0 0 255\n0 1 0 1 2 3 4 5 6\n0 0 1 0 0 0 0\n"
                                             "3 0 1 2 0.5 0.5 0.5 # a colour\n4 0 1 3 2\n"),
                  "s", "k");
    CHECK(m.vertices.size() == 4);
    CHECK(m.triangles.size() == 3);
}

TEST_CASE("non-manifold faces are kept, not dropped", "[input][mesh]") {
    // Three triangles on one edge, and one triangle twice: OpenMesh duplicates vertices to keep them.
    const std::string text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\n"
                             "f 1 2 3\nf 1 2 4\nf 1 2 5\nf 1 2 3\n";
    CHECK(load_mesh(write_temp("nonmanifold.obj", text), "s", "k").triangles.size() == 4);
}

TEST_CASE("a placed mesh must stay within single precision", "[input][mesh]") {
    ObjectDesc o;
    o.mesh_resolved = std::string(SONARSIM_INPUT_DIR) + "/meshes/big_coords.obj";
    CHECK_NOTHROW(object_world_mesh(o, "s.json", "objects[0]"));
    o.scale = {1e6, 1e6, 1e6};
    CHECK(error_of([&] {
              object_world_mesh(o, "s.json", "objects[0]");
          }).rfind("s.json: objects[0].scale: scaled and placed", 0) == 0);
}

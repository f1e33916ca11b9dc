// The benchmark scenes: four from assets/scenes, six built here on generated or shared meshes (two of them
// scenes nobody tuned the sampler to: rough terrain at grazing range, small specular objects on sand), and
// the tank (assets/scenes) timed in the viewer only.
#include "bench.hpp"
#include "terrain.hpp"

#include "core/scene/params.hpp"
#include "core/scene/scene_io.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace sonarsim::bench {
namespace fs = std::filesystem;
namespace {

/// Faces declared by a PLY header (0 when the file is not a readable PLY).
long ply_faces(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::string line;
    while (std::getline(in, line) && line != "end_header") {
        std::istringstream w(line);
        std::string a, b;
        long n = 0;
        if (w >> a >> b >> n && a == "element" && b == "face") return n;
    }
    return 0;
}

long scene_triangles(const std::string& scene_file) {
    const SceneDesc s = load_scene(scene_file);
    long n = 0;
    for (const ObjectDesc& o : s.objects)
        n += o.box_m ? 12 : ply_faces(o.mesh_resolved.empty() ? o.mesh : o.mesh_resolved);
    return n;
}

void write_text(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::trunc);
    out << text;
    if (!out) throw std::runtime_error("cannot write " + path);
}

/// Writes `scene` as a scene file (meshes by absolute path) and returns its path.
std::string write_scene(const Paths& p, const std::string& name, const SceneDesc& scene) {
    const std::string path = p.work + "/scenes/" + name + ".json";
    write_text(path, scene_to_json(scene).dump(2) + "\n");
    return path;
}

ObjectDesc mesh_object(const std::string& path, const Vec3d& position, const Vec3d& orientation_deg,
                       const Vec3d& scale) {
    ObjectDesc o;
    o.mesh = path;
    o.position_m = position;
    o.orientation_deg = orientation_deg;
    o.scale = scale;
    return o;
}

/// Procedural terrain (bench/terrain.cpp), n x n vertices, generated on first use; `rough`: the rough one.
std::string terrain_mesh(const Paths& p, int n, const std::function<void(const std::string&)>& log,
                         bool rough = false) {
    const std::string path = p.work + (rough ? "/rough_" : "/terrain_") + std::to_string(n) + ".ply";
    if (!fs::exists(path)) {
        log("generating " + path + " (" + std::to_string(terrain_triangles(n)) + " triangles)");
        write_terrain_ply(path, n, rough);
    }
    return path;
}

/// ARIS-like sonar (the paper's defaults: 128 beams, 32 x 14 deg) at 1.8 MHz, 3 m above the terrain,
/// pitched 45 deg down.
SceneDesc terrain_scene(const std::string& mesh) {
    SceneDesc s = default_scene();
    s.seafloor.reset();
    s.objects = {mesh_object(mesh, {0, 0, 0}, {0, 0, 0}, {1, 1, 1})};
    s.sonar.pose.position_m = {0, 0, terrain_height_m(0, 0) + 3.0};
    s.sonar.pose.orientation_deg = {0, 45, 30};
    s.sonar.frequency_khz = 1800;
    s.sonar.range_min_m = 1.0;
    s.sonar.range_max_m = 9.0;
    s.display.lo_db = 70;
    s.display.hi_db = 125;
    return s;
}

/// An Oculus M750d-class wide sonar, pitched 10 deg down: 750 kHz, 512 beams, 130 x 20 deg, 1 m to
/// `range_max_m` in 1500 bins, shown over 25-100 dB.
void wide_sonar(SceneDesc& s, double range_max_m) {
    s.sonar.pose.orientation_deg = {0, 10, 0};
    s.sonar.frequency_khz = 750;
    s.sonar.beams = 512;
    s.sonar.azimuth_fov_deg = 130;
    s.sonar.elevation_fov_deg = 20;
    s.sonar.range_min_m = 1;
    s.sonar.range_max_m = range_max_m;
    s.sonar.range_bins = 1500;
    s.display.lo_db = 25;
    s.display.hi_db = 100;
}

BenchScene entry(std::string name, std::string title, std::string file, bool heavy = false,
                 bool view = false) {
    BenchScene b;
    b.name = std::move(name), b.title = std::move(title), b.file = std::move(file);
    b.heavy = heavy, b.view = view;
    return b;
}

} // namespace

std::vector<BenchScene> prepare_scenes(const Paths& p, const std::function<bool(const BenchScene&)>& wanted,
                                       const std::function<void(const std::string&)>& log) {
    fs::create_directories(p.work + "/scenes");
    const std::string assets = p.repo + "/assets/scenes/";
    const std::string bunny_mesh = p.shared + "/meshes/bunny_stanford_subdiv16_1M.ply";
    std::vector<BenchScene> v;
    std::vector<std::function<std::string()>> make; // writes what the scene needs, returns its file

    v.push_back(
        entry("fig9",
              "paper Fig. 9: 70 x 120 x 220 mm prism on a flat floor, ARIS 3000 (128 beams, 32 x 14 deg, "
              "0.5-5 m), pose 1",
              "", false, true));
    make.push_back([&] { return assets + "fig9.json"; });

    v.push_back(entry(
        "floor", "bare flat floor, sonar 1 m above, pitch 30 deg (reference: the semi-analytic integral)", "",
        false, true));
    make.push_back([&] { return assets + "floor.json"; });

    v.push_back(
        entry("terrain200k",
              "procedural terrain 40 x 40 m (317 x 317 grid), ARIS-like 1.8 MHz, 3 m above, pitch 45 deg, "
              "1-9 m",
              ""));
    make.push_back([&] { return write_scene(p, "terrain200k", terrain_scene(terrain_mesh(p, 317, log))); });

    v.push_back(entry("terrain2M", "the same terrain and sonar on a 1001 x 1001 grid", "", true, true));
    make.push_back([&] { return write_scene(p, "terrain2M", terrain_scene(terrain_mesh(p, 1001, log))); });

    v.push_back(
        entry("shipwreck",
              "DAVE sunken ship (17 m) on a sand floor, 1.2 MHz, 256 beams, 60 x 20 deg, 1-25 m, ~15 m away",
              "", false, true));
    make.push_back([&] { return assets + "shipwreck.json"; });

    v.push_back(
        entry("monterey",
              "Monterey Bay bathymetry tile (1 x 1.2 km, 8-10 m grid), 900 kHz, 256 beams, 90 x 20 deg, "
              "2-100 m, 15 m above the canyon floor",
              "", false, true));
    make.push_back([&] { return assets + "monterey.json"; });

    // The 1.1 M-triangle bunny (Stanford terms: not shipped here), stood on a floor (Y-up -> Z-up: roll 90).
    v.push_back(
        entry("bunny",
              "Stanford bunny subdivided to 1.1 M triangles (15 cm), stood on a floor, ARIS 3000 at 0.7 m, "
              "0.2-1.2 m",
              "", true));
    if (!fs::exists(bunny_mesh))
        v.back().skip = bunny_mesh + " not found (the shared mesh collection is absent)";
    make.push_back([&] {
        SceneDesc s = default_scene();
        // Bounds after roll 90: x -0.0947..0.0610, y -0.0588..0.0619, z 0.0330..0.1873: centre it on the
        // origin and put its lowest point on the floor.
        s.objects = {mesh_object(bunny_mesh, {0.0168, -0.0016, -0.0330}, {90, 0, 0}, {1, 1, 1})};
        s.sonar.pose.position_m = {-0.7, 0, 0.3};
        s.sonar.pose.orientation_deg = {0, 18, 0};
        s.sonar.range_min_m = 0.2;
        s.sonar.range_max_m = 1.2;
        return write_scene(p, "bunny", s);
    });

    // Oculus M750d-class wide sonar over the 200k terrain scaled to 240 x 240 m (relief x2).
    v.push_back(
        entry("oculus",
              "Oculus-class: 512 beams, 130 x 20 deg, 1-120 m, 1500 bins, 750 kHz, 10 m above the 200k "
              "terrain scaled to 240 x 240 m, pitch 10 deg",
              "", true));
    make.push_back([&] {
        SceneDesc s = default_scene();
        s.seafloor.reset();
        const double sx = 6, sz = 2;
        s.objects = {mesh_object(terrain_mesh(p, 317, log), {0, 0, 0}, {0, 0, 0}, {sx, sx, sz})};
        s.sonar.pose.position_m = {-110, 0, sz * terrain_height_m(-110 / sx, 0) + 10};
        wide_sonar(s, 120);
        return write_scene(p, "oculus", s);
    });

    // Scenes nobody tuned the sampler to (issue 43's): a wide sonar over rough terrain at grazing range, and
    // small specular objects on sand.
    v.push_back(entry("rough",
                      "wide sonar over rough terrain at grazing range: 512 beams, 130 x 20 deg, 1-80 m, 1500 "
                      "bins, 750 kHz, 7.5 m above a 240 x 240 m, 180 k-triangle rough terrain, pitch 10 deg",
                      "", true));
    make.push_back([&] {
        SceneDesc s = default_scene();
        s.seafloor.reset();
        const int n = 301;
        s.objects = {mesh_object(terrain_mesh(p, n, log, true), {0, 0, 0}, {0, 0, 0}, {1, 1, 1})};
        apply_setting_text(s, "objects.0.material.preset=sand", "bench");
        const int i0 = int(std::lround((-100 + kRoughSize_m / 2) / kRoughSize_m * (n - 1)));
        s.sonar.pose.position_m = {-100, 0, rough_height_m(i0, (n - 1) / 2, n) + 7.5};
        wide_sonar(s, 80);
        return write_scene(p, "rough", s);
    });

    const std::string torpedo = p.shared + "/meshes/object_torpedo_mk46_dave.ply",
                      uxo = p.shared + "/meshes/object_uxo_a_dave.ply";
    v.push_back(
        entry("objects",
              "a torpedo and a UXO (DAVE meshes from ../shared) with specular lobes on sand, 1.8 MHz, "
              "128 beams, 28 x 14 deg, 0.7-9 m, 800 bins, 1.6 m above, pitch 16 deg",
              "", true));
    if (!fs::exists(torpedo) || !fs::exists(uxo))
        v.back().skip = torpedo + " or " + uxo + " not found (the shared mesh collection is absent)";
    make.push_back([&] {
        SceneDesc s = default_scene();
        apply_setting_text(s, "seafloor.material.preset=sand", "bench");
        ObjectDesc a = mesh_object(torpedo, {0.5, 0.3, 0.16}, {0, 0, 35}, {1, 1, 1});
        a.material.nu_db = -30, a.material.q = 1, a.material.mu = 50, a.material.h_deg = 3;
        ObjectDesc b = mesh_object(uxo, {1.5, -1.0, 0.17}, {0, 0, -60}, {1, 1, 1});
        b.material.nu_db = -28, b.material.q = 1, b.material.mu = 20, b.material.h_deg = 4;
        s.objects = {a, b};
        s.sonar.pose.position_m = {-4.0, 0.6, 1.6};
        s.sonar.pose.orientation_deg = {0, 16, -8};
        s.sonar.frequency_khz = 1800;
        s.sonar.beams = 128;
        s.sonar.azimuth_fov_deg = 28;
        s.sonar.elevation_fov_deg = 14;
        s.sonar.range_min_m = 0.7;
        s.sonar.range_max_m = 9.0;
        s.sonar.range_bins = 800;
        s.display.lo_db = 60;
        s.display.hi_db = 150;
        return write_scene(p, "objects", s);
    });

    // The example scenes left: timed in the viewer only.
    v.push_back(
        entry("tank",
              "multipath tank: walls and a water surface as mirrors, Oculus M750d (256 beams), bounces 1 "
              "(viewer only; `sonarsim_bench multipath` measures its image)",
              "", true, true));
    v.back().view_only = true;
    make.push_back([&] { return assets + "tank.json"; });

    for (size_t i = 0; i < v.size(); ++i)
        if (v[i].skip.empty() && wanted(v[i])) {
            v[i].file = make[i]();
            v[i].triangles = scene_triangles(v[i].file);
        }
    return v;
}

} // namespace sonarsim::bench

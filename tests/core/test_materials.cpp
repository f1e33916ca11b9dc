// Material presets (assets/materials/*.json): each parses with a source for every value, gives the values
// docs/model.md documents, applies before a surface's explicit keys, rejects unknown names, and a floor of
// sand renders brighter than one of mud by the GSAB law's difference at each bin's incidence.
#include "core/base/errors.hpp"
#include "core/scene/materials.hpp"
#include "core/pipeline/simulator.hpp"
#include "core/scene/params.hpp"
#include "core/scene/sampling_scheme.hpp"
#include "core/scene/scene_io.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <string>

using namespace sonarsim;

namespace {

/// The values docs/model.md lists (NaN: the preset leaves the key alone).
struct Documented {
    double nu_db, q, reflection_db;
};
const double kUnset = std::numeric_limits<double>::quiet_NaN();
const std::map<std::string, Documented> kDocumented = {{"sand", {-16.2, 2.26, kUnset}},
                                                       {"mud", {-26.1, 1.29, kUnset}},
                                                       {"gravel", {-8.2, 2.04, kUnset}},
                                                       {"rock", {-15.7, 2.0, kUnset}},
                                                       {"hull", {kUnset, kUnset, 0.0}}};

/// `documented` where set, else the default material's value.
double expected(double documented, double fallback) {
    return std::isnan(documented) ? fallback : documented;
}

/// Every field of `m` equals the default material's except the documented ones, which equal theirs.
void check_documented(const Material& m, const std::string& name) {
    const Documented& d = kDocumented.at(name);
    const Material def;
    INFO(name);
    CHECK(m.preset == name);
    CHECK(m.nu_db == expected(d.nu_db, def.nu_db));
    CHECK(m.q == expected(d.q, def.q));
    CHECK(m.reflection_db == expected(d.reflection_db, def.reflection_db));
    for (const MaterialSpec& spec : material_params()) {
        if (spec.key == "nu_db" || spec.key == "q" || spec.key == "reflection_db") continue;
        INFO(spec.key);
        CHECK(m.*(spec.field) == def.*(spec.field));
    }
}

} // namespace

TEST_CASE("materials: the five presets parse, each value a material key with a source", "[materials]") {
    std::set<std::string> names;
    for (auto& p : material_presets()) {
        INFO(p.file);
        names.insert(p.name);
        CHECK(p.file == "assets/materials/" + p.name + ".json");
        CHECK(!p.sources.empty());
        CHECK(p.notes.find("Not set") != std::string::npos); // what it leaves alone, and why
        for (auto& v : p.values) {
            INFO(v.key);
            REQUIRE(find_material_param(v.key));
            CHECK(v.source.size() >= 10);
        }
    }
    CHECK(names == std::set<std::string>{"gravel", "hull", "mud", "rock", "sand"});
    CHECK(material_preset_choices() ==
          std::vector<std::string>{"none", "gravel", "hull", "mud", "rock", "sand"});
    CHECK(material_preset_param().choices == material_preset_choices());
}

TEST_CASE("materials: a preset file with an unknown key, a value out of range or no source is an error",
          "[materials]") {
    const std::string file = "assets/materials/test.json";
    json j = {{"name", "test"},
              {"title", "a test"},
              {"notes", "Not set: everything else"},
              {"values", {{"nu_db", {{"value", -20}, {"source", "a measurement somewhere"}}}}},
              {"sources", {{{"citation", "[X] somebody"}, {"used_for", "nu_db"}}}}};
    CHECK(parse_material_preset(file, j.dump()).values.at(0).value == -20);
    json bad = j;
    bad["values"]["colour"] = {{"value", 1}, {"source", "a measurement somewhere"}};
    CHECK_THROWS_WITH(parse_material_preset(file, bad.dump()),
                      Catch::StartsWith(file + ": values.colour: not a material key; allowed: nu_db, q"));
    bad = j, bad["values"]["q"] = {{"value", -1}, {"source", "a measurement somewhere"}};
    CHECK_THROWS_WITH(parse_material_preset(file, bad.dump()), Catch::Contains("values.q.value"));
    bad = j, bad["values"]["nu_db"].erase("source");
    CHECK_THROWS_WITH(parse_material_preset(file, bad.dump()), Catch::Contains("values.nu_db.source"));
    bad = j, bad["sources"] = json::array();
    CHECK_THROWS_WITH(parse_material_preset(file, bad.dump()), Catch::Contains(file + ": sources"));
    bad = j, bad["name"] = "other";
    CHECK_THROWS_WITH(parse_material_preset(file, bad.dump()), Catch::Contains("name: must be \"test\""));
}

TEST_CASE("materials: loading each preset gives the documented values on every kind of surface",
          "[materials]") {
    for (auto& [name, d] : kDocumented) {
        const std::string m = R"({"preset": ")" + name + R"("})";
        const SceneDesc s =
            parse_scene(R"({"seafloor": {"height_m": 0, "material": )" + m +
                            R"(}, "water": {"surface_height_m": 3, "surface_material": )" + m +
                            R"(}, "objects": [{"box": [1, 1, 1], "material": )" + m + "}]}",
                        "scene.json", ".");
        check_documented(s.seafloor->material, name);
        check_documented(s.objects.at(0).material, name);
        check_documented(s.water.surface_material, name);
        SceneDesc t = default_scene();
        apply_setting(t, "objects.0.material.preset", name, "--set");
        check_documented(t.objects[0].material, name);
    }
}

TEST_CASE("materials: the surface's explicit keys override its preset, whatever their order", "[materials]") {
    // "nu_db" sorts before "preset": the preset still applies first.
    const SceneDesc s = parse_scene(
        R"({"seafloor": {"height_m": 0, "material": {"nu_db": -30, "preset": "sand", "texture_rms_db": 2}}})",
        "scene.json", ".");
    const Material& m = s.seafloor->material;
    CHECK(m.preset == "sand");
    CHECK(m.nu_db == -30);
    CHECK(m.q == 2.26);
    CHECK(m.texture_rms_db == 2);
    // Written and read back: the same material (the file lists the preset and every value).
    const SceneDesc back = parse_scene(scene_to_json(s).dump(), "back.json", ".");
    CHECK(scene_to_json(back) == scene_to_json(s));
    CHECK(back.seafloor->material.nu_db == -30);
    // --set applies in order; "none" keeps the values and drops the name.
    SceneDesc t = s;
    apply_setting(t, "seafloor.material.preset", "mud", "--set");
    CHECK(t.seafloor->material.nu_db == -26.1);
    CHECK(t.seafloor->material.texture_rms_db == 2); // mud does not set it
    apply_setting(t, "seafloor.material.preset", "none", "--set");
    CHECK(t.seafloor->material.preset == "none");
    CHECK(t.seafloor->material.q == 1.29);
}

TEST_CASE("materials: an unknown preset is an error naming the file, the key and the presets",
          "[materials]") {
    CHECK_THROWS_WITH(
        parse_scene(R"({"seafloor": {"height_m": 0, "material": {"preset": "sandy"}}})", "floor.json", "."),
        "floor.json: seafloor.material.preset: got \"sandy\"; allowed: one of \"none\", \"gravel\", "
        "\"hull\", "
        "\"mud\", \"rock\", \"sand\"");
    SceneDesc s = default_scene();
    CHECK_THROWS_WITH(apply_setting(s, "objects.0.material.preset", 3, "--set"),
                      Catch::StartsWith("--set: objects.0.material.preset: got a number"));
    CHECK_THROWS_WITH(apply_setting(s, "objects.0.material.colour", 3, "--set"),
                      Catch::Contains("unknown key; allowed: preset, nu_db, q"));
}

TEST_CASE("materials: sand over mud on a flat floor is the GSAB difference at each bin's incidence",
          "[materials]") {
    // A flat floor at z = 0 seen from height H: every echo of range r arrives at incidence cos(theta) = H /
    // r, whatever its direction, so two renders that differ only in the floor's material differ in every
    // range bin by 10 log10 (S_sand / S_mud) = (nu_sand - nu_mud) + (q_sand - q_mud) 10 log10 (H / r) (mu =
    // 0).
    const double H = 1.0;
    SceneDesc s = default_scene();
    s.objects.clear();
    s.seafloor = Seafloor{};
    s.sonar.pose.position_m = {0, 0, H};
    s.sonar.pose.orientation_deg = {0, 30, 0};
    set_scheme(s.sampling, SamplingScheme::Spread);
    SceneDesc mud = s;
    apply_setting(s, "seafloor.material.preset", "sand", "--set");
    apply_setting(mud, "seafloor.material.preset", "mud", "--set");
    const auto a = Simulator(s).render(), b = Simulator(mud).render();
    const PolarImage &ia = a->ideal(), &ib = b->ideal();
    const Documented &ds = kDocumented.at("sand"), &dm = kDocumented.at("mud");
    const double dr = (s.sonar.range_max_m - s.sonar.range_min_m) / ia.bins;
    int checked = 0;
    for (const double incidence_deg : {55.0, 60.0, 65.0}) {
        const double r = H / std::cos(incidence_deg * M_PI / 180);
        const int k = int((r - s.sonar.range_min_m) / dr);
        const double r_k = s.sonar.range_min_m + (k + 0.5) * dr;
        double ea = 0, eb = 0;
        for (int i = 0; i < ia.beams; ++i) {
            if (!std::isfinite(ia.at(k, i)) || !std::isfinite(ib.at(k, i))) continue;
            ea += std::pow(10.0, ia.at(k, i) / 10), eb += std::pow(10.0, ib.at(k, i) / 10);
        }
        INFO("incidence " << incidence_deg << " deg, bin " << k << " at " << r_k << " m");
        REQUIRE(ea > 0);
        const double closed_form = (ds.nu_db - dm.nu_db) + (ds.q - dm.q) * 10 * std::log10(H / r_k);
        CHECK(10 * std::log10(ea / eb) == Approx(closed_form).margin(0.01));
        ++checked;
    }
    CHECK(checked == 3);
}

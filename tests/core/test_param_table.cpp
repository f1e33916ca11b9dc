// The parameter table end to end: every key round-trips through scene_to_json and apply_setting, and an edit
// of any row recomputes exactly the row's effective stage, re-using the earlier ones.
#include "core/base/errors.hpp"
#include "core/pipeline/simulator.hpp"
#include "core/scene/sampling_scheme.hpp"
#include "core/scene/scene_io.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

using namespace sonarsim;

namespace {

/// A small scene with every part: a box, a mesh-free floor and a water surface (so that its material is
/// written), cheap enough to render once per row.
SceneDesc small_scene(SamplingScheme scheme) {
    SceneDesc s = default_scene();
    s.sonar.beams = 32, s.sonar.range_bins = 128;
    s.sampling.elevation_rays = 40;
    set_scheme(s.sampling, scheme);
    s.water.surface_height_m = 3.0;
    s.objects[0].name = "prism";
    return s;
}

/// One key of the table: its full key path, its value in `scene` and the stage an edit of it costs.
struct Key {
    std::string path;
    json value;
    const ValueSpec* spec;
    std::function<Stage(const SceneDesc& before, const SceneDesc& after)> stage;
};

std::vector<Key> all_keys(const SceneDesc& s) {
    std::vector<Key> keys;
    for (auto& p : scene_params())
        keys.push_back({p.key, p.get(s), &p,
                        [&p](const SceneDesc&, const SceneDesc& b) { return p.effective_stage(b); }});
    auto materials = [&](const std::string& prefix, std::function<const Material&(const SceneDesc&)> of) {
        for (auto& p : material_params())
            keys.push_back(
                {prefix + p.key, p.get(of(s)), &p, [&p, of](const SceneDesc& a, const SceneDesc& b) {
                     return p.stage_of_change(of(a).*p.field, of(b).*p.field, b);
                 }});
    };
    materials("water.surface_material.",
              [](const SceneDesc& x) -> const Material& { return x.water.surface_material; });
    materials("seafloor.material.",
              [](const SceneDesc& x) -> const Material& { return x.seafloor->material; });
    materials("objects.0.material.",
              [](const SceneDesc& x) -> const Material& { return x.objects[0].material; });
    for (auto& p : object_params())
        keys.push_back({"objects.0." + p.key, p.get(s.objects[0]), &p,
                        [&p](const SceneDesc&, const SceneDesc& b) { return p.effective_stage(b); }});
    for (auto& p : seafloor_params())
        keys.push_back({"seafloor." + p.key, p.get(*s.seafloor), &p,
                        [&p](const SceneDesc&, const SceneDesc& b) { return p.effective_stage(b); }});
    return keys;
}

/// Values different from `v` that the row may accept (the first valid one is used).
std::vector<json> other_values(const ValueSpec& spec, const json& v) {
    switch (spec.type) {
    case ParamType::Number:
    case ParamType::Integer: {
        if (v.is_null()) return {json(6.0)};
        const double x = v.get<double>();
        std::vector<json> out;
        for (double c : {x * 1.1, x * 0.9, x + 1, x - 1, x + 0.01, x - 0.01})
            out.push_back(spec.type == ParamType::Integer ? json(std::round(c)) : json(c));
        return out;
    }
    case ParamType::Vec3: {
        if (v.is_null()) return {};
        json a = v, b = v;
        a[0] = a[0].get<double>() * 1.1 + 0.01;
        b[2] = b[2].get<double>() * 0.9 - 0.01;
        return {a, b};
    }
    case ParamType::Bool:
        return {json(!v.get<bool>())};
    case ParamType::Enum: {
        std::vector<json> out;
        for (auto& c : spec.choices)
            if (json(c) != v) out.push_back(json(c));
        return out;
    }
    case ParamType::String:
        return v.is_null() ? std::vector<json>{} : std::vector<json>{json(v.get<std::string>() + "x")};
    }
    return {};
}

} // namespace

TEST_CASE("every key round-trips: scene_to_json, then apply_setting of its value, gives the same scene",
          "[params]") {
    const SceneDesc s = small_scene(SamplingScheme::Adaptive);
    const json j = scene_to_json(s);
    Simulator sim(s);
    const auto first = sim.render();
    size_t written = 0;
    for (const Key& k : all_keys(s)) {
        INFO(k.path << " = " << k.value.dump());
        // The value as scene_to_json writes it (a name, a label, is not written: its own value).
        json v = k.value;
        const json::json_pointer ptr("/" + [&] {
            std::string p = k.path;
            for (auto& c : p)
                if (c == '.') c = '/';
            return p;
        }());
        if (j.contains(ptr)) v = j.at(ptr), ++written;
        if (v.is_null() && !k.spec->optional) continue; // absent: the mesh of a box
        SceneDesc t = s;
        CHECK(apply_setting(t, k.path, v, "test") == Stage::None);
        CHECK(scene_to_json(t) == j);
        CHECK(changed_stage(s, t) == Stage::None);
        sim.set_scene(t);
        CHECK(sim.pending() == Stage::None);
        const auto again = sim.render();
        CHECK(again->sector_ptr == first->sector_ptr);
        CHECK(again->sector().pixels == first->sector().pixels);
    }
    size_t used = 0; // the rows of the scene's kind: those of the other kinds are not written
    for (auto& p : scene_params()) used += p.used_by(s.sonar.kind);
    CHECK(written > used + 3 * material_params().size());
}

TEST_CASE("an edit of any row recomputes exactly its effective stage and re-uses the earlier ones",
          "[params][simulator]") {
    for (SamplingScheme scheme : {SamplingScheme::Adaptive, SamplingScheme::Uniform}) {
        const SceneDesc s = small_scene(scheme);
        Simulator sim(s);
        const auto first = sim.render();
        size_t edited = 0;
        for (const Key& k : all_keys(s)) {
            if (is_group_key(k.path)) continue; // they cost what the rows they set cost
            SceneDesc t = s;
            json used;
            for (const json& v : other_values(*k.spec, k.value)) {
                if (v == k.value) continue;
                try {
                    SceneDesc u = s;
                    apply_setting(u, k.path, v, "test");
                    validate_scene(u, "test");
                    t = u, used = v;
                    break;
                } catch (const InputError&) {
                }
            }
            INFO(k.path << ": " << k.value.dump() << " -> " << used.dump() << ", scheme " << int(scheme));
            if (used.is_null()) continue;
            ++edited;
            const Stage expected = k.stage(s, t);
            SceneDesc u = s;
            CHECK(apply_setting(u, k.path, used, "test") == expected);
            CHECK(changed_stage(s, t) == expected);
            if (expected == Stage::None) continue; // a label
            Simulator inc(s);
            const auto before = inc.render();
            inc.set_scene(t);
            CHECK(inc.pending() == std::max(expected, Stage::Trace));
            const auto after = inc.render();
            CHECK((after->hits_ptr == before->hits_ptr) == (expected > Stage::Place)); // Place: re-traced
            CHECK((after->ideal_ptr == before->ideal_ptr) == (expected > Stage::Shade));
            if (after->sensor_applied()) // else the polar image is the ideal one
                CHECK((after->polar_ptr == before->polar_ptr) == (expected > Stage::Sensor));
            Simulator fresh(t);
            const auto ref = fresh.render();
            CHECK(after->polar().level_db == ref->polar().level_db);
            CHECK(after->sector().pixels == ref->sector().pixels);
        }
        CHECK(edited > scene_params().size());
    }
}

TEST_CASE("each row's slider range holds its default and lies within the row's bounds", "[params]") {
    SceneDesc s = default_scene();
    s.water.surface_height_m = 3.0; // so that the surface's material is a key
    int numeric = 0;
    for (const Key& k : all_keys(s)) {
        const ValueSpec& spec = *k.spec;
        if (spec.type != ParamType::Number && spec.type != ParamType::Integer && spec.type != ParamType::Vec3)
            continue;
        ++numeric;
        INFO(k.path);
        const SliderRange r = spec.slider_range();
        CHECK(r.lo < r.hi);
        if (r.logarithmic) CHECK(r.lo > 0);
        // Both ends are values the row accepts (exclusive bounds included).
        ValueSpec one = spec;
        one.type = spec.type == ParamType::Integer ? ParamType::Integer : ParamType::Number;
        CHECK_NOTHROW(validate_value(one, json(r.lo), "test", k.path));
        CHECK_NOTHROW(validate_value(one, json(r.hi), "test", k.path));
        // The default is on the slider (an absent value, such as a box's size on a mesh, has none).
        const json& v = k.value;
        const std::vector<double> xs = v.is_null()    ? std::vector<double>{}
                                       : v.is_array() ? v.get<std::vector<double>>()
                                                      : std::vector<double>{v.get<double>()};
        for (double x : xs) {
            CHECK(x >= r.lo);
            CHECK(x <= r.hi);
        }
    }
    CHECK(numeric > 50);
    // A range worth sweeping where one was chosen: the frequency's, logarithmic in [100, 5000] kHz.
    const SliderRange f = find_param("sonar.frequency_khz")->slider_range();
    CHECK(f.lo == 100);
    CHECK(f.hi == 5000);
    CHECK(f.logarithmic);
    // Without one, the row's bounds.
    const SliderRange b = find_param("sampling.bounces")->slider_range();
    CHECK(b.lo == 0);
    CHECK(b.hi == 2);
}

TEST_CASE("labels and sections of the viewer's controls come from the table", "[params]") {
    CHECK(find_param("sonar.frequency_khz")->label_text() == "f frequency [kHz]");
    CHECK(find_param("sonar.range_max_m")->label_text() == "range max [m]");
    CHECK(find_param("sampling.bounces")->label_text() == "bounces");
    CHECK(find_material_param("nu_db")->label_text() == "10 log nu [dB]");
    CHECK(find_param("sonar.position")->section == Section::Pose);
    CHECK(find_param("sonar.beams")->section == Section::Sonar);
    CHECK(find_param("water.depth_m")->section == Section::Water);
    CHECK(find_param("sensor.gain_db")->section == Section::Sensor);
    CHECK(find_param("export.lo_db")->section == Section::None);
    CHECK(find_param("sonar.angular_rate_dps")->section == Section::Motion);
    CHECK(find_param("sonar.motion_from_trajectory")->section == Section::None); // batch only
    CHECK(find_material_param("q")->section == Section::Material);
    CHECK(find_object_param("scale")->section == Section::Object);
    CHECK(std::string(section_title(Section::Material)) == "Object / material");
}

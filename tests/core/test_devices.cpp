// Device presets (assets/devices/*.json): each parses, sets only parameter-table keys with valid values and
// sources, applies through sonar.device, and renders a visible image of a floor with the device sensor.
#include "core/scene/devices.hpp"
#include "core/scene/sampling_scheme.hpp"
#include "core/base/errors.hpp"
#include "core/base/file_io.hpp"
#include "core/display/image.hpp"
#include "core/scene/params.hpp"
#include "core/scene/scene_io.hpp"
#include "core/pipeline/simulator.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <set>
#include <string>
#include <vector>

using namespace sonarsim;

namespace {

const DeviceValue* value_of(const DevicePreset& p, const std::string& key) {
    for (auto& v : p.values)
        if (v.key == key) return &v;
    return nullptr;
}

double number_of(const DevicePreset& p, const std::string& key) {
    const DeviceValue* v = value_of(p, key);
    REQUIRE(v);
    return v->value.get<double>();
}

bool starts_with(const std::string& s, const std::string& prefix) {
    return s.rfind(prefix, 0) == 0;
}

/// A scene with only a flat seafloor at z = 0, the sonar `name` with the device sensor, pitched 10 deg down
/// at the height where its fan's centre meets the floor at mid-window.
SceneDesc floor_scene(const std::string& name) {
    SceneDesc s = default_scene();
    s.objects.clear();
    s.seafloor = Seafloor{};
    apply_setting(s, "sonar.device", name, "--set");
    apply_setting(s, "sensor.model", "device", "--set");
    const double pitch_deg = 10, r_mid = 0.5 * (s.sonar.range_min_m + s.sonar.range_max_m);
    s.sonar.pose.position_m = {0, 0, r_mid * std::sin(pitch_deg * M_PI / 180)};
    s.sonar.pose.orientation_deg = {0, pitch_deg, 0};
    // The sampling scheme is not what this test is about: spread is quick and leaves no bin empty.
    set_scheme(s.sampling, SamplingScheme::Spread);
    validate_scene(s, "test");
    return s;
}

/// Median of the finite values of `v` (-inf when there are none).
double median(std::vector<double> v) {
    v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }), v.end());
    if (v.empty()) return -INFINITY;
    std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
    return v[v.size() / 2];
}

/// Median level [dB] over the central half of the beams in the bins [k0, k1).
double median_level(const PolarImage& img, int k0, int k1) {
    std::vector<double> v;
    for (int k = k0; k < k1; ++k)
        for (int b = img.beams / 4; b < 3 * img.beams / 4; ++b) v.push_back(img.at(k, b));
    return median(v);
}

const char* const kRequired[] = {"aris3000-hf",      "aris3000-lf",     "aris1800-hf",
                                 "aris1800-lf",      "aris1200",        "didson300-hf",
                                 "oculus-m750d-lf",  "oculus-m750d-hf", "oculus-m1200d-lf",
                                 "oculus-m1200d-hf", "gemini-720is",    "blueview-m900-130"};

} // namespace

TEST_CASE("devices: every preset parses and the required ones exist", "[devices]") {
    const auto& presets = device_presets();
    for (const char* name : kRequired) {
        INFO(name);
        CHECK(find_device(name));
    }
    std::set<std::string> names;
    for (auto& p : presets) {
        INFO(p.file);
        CHECK(names.insert(p.name).second);
        CHECK(p.file == "assets/devices/" + p.name + ".json");
        CHECK(!p.title.empty());
        CHECK(!p.values.empty());
    }
    const auto choices = device_choices();
    CHECK(choices.front() == "none");
    CHECK(choices.size() == presets.size() + 1);
}

TEST_CASE("devices: every preset value is a table key with a valid value and a source", "[devices]") {
    for (auto& p : device_presets()) {
        std::set<std::string> keys;
        for (auto& v : p.values) {
            INFO(p.file << ": " << v.key);
            CHECK(keys.insert(v.key).second);
            const ParamSpec* spec = find_param(v.key);
            REQUIRE(spec);
            CHECK_NOTHROW(validate_value(*spec, v.value, p.file, v.key));
            CHECK(v.source.size() >= 10);
            CHECK(spec->preset_may_set); // parse_device_preset rejects any other
        }
        INFO(p.file);
        // The main figures every preset gives, and the display that never renders black.
        for (const char* key :
             {"sonar.frequency_khz", "sonar.azimuth_fov_deg", "sonar.elevation_fov_deg", "sonar.range_min_m",
              "sonar.range_max_m", "sonar.range_bins", "sonar.source_level_db", "sonar.noise_level_db",
              "sensor.range_resolution_m"}) {
            INFO(key);
            CHECK(value_of(p, key));
        }
        // An imaging sonar's beams; a side-scan's tilt; a scanning head's step and its time.
        const std::vector<const char*> of_kind =
            p.kind() == "imaging" ? std::vector<const char*>{"sonar.beams", "sensor.azimuth_beamwidth_deg"}
            : p.kind() == "sidescan"
                ? std::vector<const char*>{"sidescan.depression_deg"}
                : std::vector<const char*>{"scanning.step_deg", "scanning.step_overhead_ms"};
        for (const char* key : of_kind) {
            INFO(key);
            CHECK(value_of(p, key));
        }
        REQUIRE(value_of(p, "display.auto"));
        CHECK(value_of(p, "display.auto")->value == true);
        CHECK(number_of(p, "sonar.range_min_m") < number_of(p, "sonar.range_max_m"));
        CHECK(number_of(p, "sonar.range_bins") <= 2048);
        // Options that only mean something with the choice they belong to.
        if (auto* t = value_of(p, "sensor.taylor_sidelobe_db")) {
            REQUIRE(value_of(p, "sensor.azimuth_window"));
            CHECK(value_of(p, "sensor.azimuth_window")->value == "taylor");
            CHECK(t->value.get<double>() < 0);
        }
        if (value_of(p, "sensor.speckle_k_shape")) {
            REQUIRE(value_of(p, "sensor.speckle"));
            CHECK(value_of(p, "sensor.speckle")->value == "k");
        }
    }
}

TEST_CASE("devices: the keys a preset may set are the device's, one column of the table", "[devices]") {
    // What a preset must leave to the scene: the pose and its motion, the choice of device and sensor, the
    // seed, the sampler, the water, the exports, a waterfall's length and range and a scan's sector. A
    // preset names its kind.
    for (const ParamSpec& p : scene_params()) {
        INFO(p.key);
        const bool scene_choice =
            (is_group_key(p.key) && p.key != "sonar.kind") || p.type == ParamType::Vec3 ||
            p.key == "sonar.motion_from_trajectory" || p.key == "sensor.seed" ||
            starts_with(p.key, "sampling.") || starts_with(p.key, "water.") ||
            starts_with(p.key, "export.") || p.key == "sidescan.pings" || p.key == "sidescan.range" ||
            p.key == "sidescan.bottom_threshold_db" || starts_with(p.key, "scanning.sector_");
        CHECK(p.preset_may_set == !scene_choice);
    }
    for (const ParamSpec& p : input_params()) CHECK_FALSE(p.preset_may_set);
    CHECK(starts_with(preset_keys_text(), "sonar.frequency_khz, sonar.azimuth_fov_deg, "));
}

TEST_CASE("devices: a preset setting a key presets may not set is an error naming file, key and the allowed",
          "[devices]") {
    const std::string file = SONARSIM_TEST_DATA "/devices/seeded.json";
    const std::string text = read_file_bytes(file);
    try {
        parse_device_preset(file, text);
        FAIL("no error");
    } catch (const InputError& e) {
        const std::string what = e.what();
        CHECK(what.rfind(file +
                             ": values.sensor.seed: a device preset may not set this key; presets may set: "
                             "sonar.frequency_khz, ",
                         0) == 0);
        CHECK(what.find("sensor.gain_db") != std::string::npos);
        CHECK(what.find("sensor.seed", what.find("presets may set")) == std::string::npos);
    }
    // The same file without the seed is a preset named after its file.
    json j = json::parse(text);
    j["values"].erase("sensor.seed");
    const DevicePreset ok = parse_device_preset(file, j.dump());
    CHECK(ok.name == "seeded");
    REQUIRE(ok.values.size() == 1);
    CHECK(ok.values[0].value == 64);
    // A key of no row, and a value out of its row's bounds, are errors too.
    j["values"]["sonar.nonsense"] = {{"value", 1}, {"sure", true}, {"source", "nowhere at all"}};
    CHECK_THROWS_WITH(parse_device_preset(file, j.dump()),
                      Catch::Contains("values.sonar.nonsense: not a parameter"));
    j["values"].erase("sonar.nonsense");
    j["values"]["sonar.beams"]["value"] = 0;
    CHECK_THROWS_WITH(parse_device_preset(file, j.dump()),
                      Catch::Contains("values.sonar.beams.value: value 0"));
}

TEST_CASE("devices: sonar.device sets the preset values and scene keys override them", "[devices]") {
    for (auto& p : device_presets()) {
        INFO(p.file);
        SceneDesc s = default_scene();
        apply_setting(s, "sonar.device", p.name, "--set");
        apply_setting(s, "sensor.model", "device", "--set");
        CHECK(s.sonar.device == p.name);
        for (auto& v : p.values) {
            INFO(v.key);
            const ParamSpec* spec = find_param(v.key);
            REQUIRE(spec);
            CHECK(spec->get(s) == validate_value(*spec, v.value, p.file, v.key));
        }
        CHECK_NOTHROW(validate_scene(s, "test"));
    }
    // In a scene file the preset comes first, whatever the order of the keys.
    const SceneDesc s =
        parse_scene(R"({"sonar": {"beams": 64, "beam_table": "uniform", "device": "oculus-m750d-lf"}})",
                    "scene.json", ".");
    CHECK(s.sonar.device == "oculus-m750d-lf");
    CHECK(s.sonar.beams == 64);
    CHECK(s.sonar.azimuth_fov_deg == 130);
    // A preset's beam table does not fit another beam count: an input error naming the table.
    CHECK_THROWS_WITH(
        parse_scene(R"({"sonar": {"beams": 64, "device": "oculus-m750d-lf"}})", "scene.json", "."),
        Catch::Contains("sonar.beam_table") && Catch::Contains("allowed for 64 beams: uniform"));
    SceneDesc t = default_scene();
    CHECK_THROWS_AS(apply_setting(t, "sonar.device", "no-such-sonar", "--set"), InputError);
}

TEST_CASE("devices: each imaging preset renders a visible floor with the device sensor", "[devices]") {
    for (auto& p : device_presets()) {
        INFO(p.name);
        if (p.kind() != "imaging") continue; // tests/core/test_kinds.cpp
        const SceneDesc s = floor_scene(p.name);
        Simulator sim(s);
        const auto frame = sim.render();
        REQUIRE(frame->sensor_applied());

        // The fan: pixels neither black nor white (the colour map's ends) make up most of it.
        const Image8& img = frame->sector();
        const SectorLayout layout(s.sonar, img.height);
        const auto black = colormap_rgb(s.display.colormap, 0), white = colormap_rgb(s.display.colormap, 1);
        size_t fan = 0, shown = 0;
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x) {
                double r, a;
                if (!layout.pixel_to_polar(x + 0.5, y + 0.5, r, a)) continue;
                const std::uint8_t* px = &img.pixels[(size_t(y) * img.width + x) * img.channels];
                const bool is_black = std::equal(black.begin(), black.end(), px);
                const bool is_white = std::equal(white.begin(), white.end(), px);
                ++fan;
                shown += !is_black && !is_white;
            }
        REQUIRE(fan > 0);
        CHECK(double(shown) / double(fan) > 0.6);

        // The automatic display range lies within the image's finite levels.
        const PolarImage& out = frame->polar();
        double lo = INFINITY, hi = -INFINITY;
        for (float v : out.level_db)
            if (std::isfinite(v)) lo = std::min(lo, double(v)), hi = std::max(hi, double(v));
        REQUIRE(std::isfinite(lo));
        CHECK(frame->display.auto_range);
        CHECK(frame->display.lo_db < frame->display.hi_db);
        CHECK(frame->display.lo_db >= lo - 1e-3);
        CHECK(frame->display.hi_db <= hi + 1e-3);

        // The preset's levels: the floor stands well above the noise (L_EN = 0 dB) at mid-window, and
        // sinks to about the noise at the far end, where the gain shows the noise.
        const PolarImage& ideal = frame->ideal();
        const int K = ideal.bins;
        const double mid = median_level(ideal, K / 2 - K / 20, K / 2 + K / 20);
        const double far = median_level(ideal, K - K / 20, K);
        CHECK(mid > 10);
        CHECK(far < 10);
    }
}

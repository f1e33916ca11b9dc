// A gray fan PNG read back by `sonarsim compare`: the levels it shows come back at every (bin, beam) where
// the image is smooth; the geometry from render's metadata and the same geometry given by hand agree; bad
// input names the field.
#include "core/scene/params.hpp"
#include "core/analysis/compare_report.hpp"
#include "core/analysis/fan_image.hpp"
#include "core/base/errors.hpp"
#include "core/display/image.hpp"
#include "core/io/output.hpp"
#include "core/pipeline/simulator.hpp"
#include "core/scene/scene_io.hpp"
#include "support.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

using namespace sonarsim;

namespace {

/// The built-in scene's fan with a fixed display range, written as render does: PREFIX.png and PREFIX.json.
std::shared_ptr<const Frame> write_fan(const std::string& prefix, SceneDesc& s,
                                       const std::string& device = "") {
    s = default_scene();
    if (!device.empty()) { // the device's beams over the built-in scene's range window
        const SonarParams window = s.sonar;
        apply_setting_text(s, ("sonar.device=" + device).c_str(), "test");
        s.sonar.range_min_m = window.range_min_m, s.sonar.range_max_m = window.range_max_m;
        s.sonar.range_bins = window.range_bins, s.sonar.source_level_db = window.source_level_db;
    }
    s.display.auto_range = false, s.display.lo_db = 60, s.display.hi_db = 110;
    Simulator sim(s);
    auto f = sim.render();
    test::write_file_bytes(prefix + ".png", encode_png(f->sector()));
    const std::string meta = frame_metadata(s, *f).dump();
    test::write_file_bytes(prefix + ".json", Bytes(meta.begin(), meta.end()));
    return f;
}

} // namespace

TEST_CASE("a gray fan PNG reads back as the levels it shows", "[compare]") {
    // The built-in scene's even beams, and a DIDSON's table, whose fan (-14.72 ... +14.09 deg) is not
    // symmetric: read back at the table's beams, not at even ones.
    const std::string device = GENERATE(as<std::string>(), "", "didson300-hf");
    INFO(device);
    SceneDesc s;
    const std::string prefix = test::out_path("fan_readback" + device);
    const auto f = write_fan(prefix, s, device);
    const PolarImage back = load_compare_image(prefix + ".png", 0);
    const PolarImage& ref = f->polar();
    REQUIRE(back.bins == ref.bins);
    REQUIRE(back.beams == ref.beams);
    const double lo = f->display.lo_db, hi = f->display.hi_db;
    // Where the level and its neighbours lie inside the display range and within 1 dB of each other, the
    // PNG shows it to 8 bits (0.2 dB here) after two interpolations.
    std::vector<double> err;
    int floor_ok = 0, floor_n = 0;
    for (int k = 1; k + 1 < ref.bins; ++k)
        for (int i = 1; i + 1 < ref.beams; ++i) {
            const double v = ref.at(k, i);
            double spread = 0, top = -INFINITY;
            for (int dk = -1; dk <= 1; ++dk)
                for (int di = -1; di <= 1; ++di) {
                    const double n = ref.at(k + dk, i + di);
                    spread = std::max(spread, std::abs(n - v)), top = std::max(top, n);
                }
            if (v > lo + 1 && v < hi - 1 && spread < 1) err.push_back(std::abs(back.at(k, i) - v));
            if (top < lo - 1) ++floor_n, floor_ok += std::isinf(back.at(k, i)) ? 1 : 0; // black: the floor
        }
    REQUIRE(err.size() > 1000);
    std::sort(err.begin(), err.end());
    CHECK(err[err.size() / 2] < 0.15);
    CHECK(err[err.size() * 95 / 100] < 0.5);
    REQUIRE(floor_n > 1000);
    CHECK(floor_ok == floor_n);

    if (!device.empty()) return; // by hand (below), the beams are even

    // The same geometry by hand: apex, scale and fan from the sector layout, the display range, the grid.
    const SectorLayout layout(s.sonar, f->sector().height);
    double ax = 0, ay = 0;
    layout.polar_to_pixel(0, 0, ax, ay);
    char spec[256];
    std::snprintf(spec, sizeof spec, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%d,%d", ax, ay,
                  1 / layout.metres_per_pixel(), s.sonar.azimuth_fov_deg, s.sonar.range_min_m,
                  s.sonar.range_max_m, lo, hi, s.sonar.beams, s.sonar.range_bins);
    CHECK(load_compare_image(prefix + ".png", 0, spec).level_db == back.level_db);
}

TEST_CASE("fan PNG input errors name the field and what is allowed", "[compare]") {
    SceneDesc s;
    const std::string prefix = test::out_path("fan_errors");
    write_fan(prefix, s);
    auto message = [&](const std::string& spec) {
        try {
            load_compare_image(prefix + ".png", 0, spec);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    CHECK(message("1,2,3").find("expected 10 numbers") != std::string::npos);
    CHECK(message("500,900,100,30,0.5,5,60,110,0,512").find("beams") != std::string::npos);
    CHECK(message("500,900,100,30,5,0.5,60,110,128,512").find("range_min_m") != std::string::npos);
    CHECK(message("500,900,1e5,30,0.5,5,60,110,128,512").find("outside") != std::string::npos);
    CHECK(message("500,x,100,30,0.5,5,60,110,128,512").find("apex_y_px") != std::string::npos);
    // A colour map cannot be read back.
    SceneDesc v = default_scene();
    v.display.colormap = Colormap::Viridis;
    Simulator sim(v);
    const auto f = sim.render();
    test::write_file_bytes(prefix + "_viridis.png", encode_png(f->sector()));
    const SectorLayout layout(v.sonar, f->sector().height);
    double ax = 0, ay = 0;
    layout.polar_to_pixel(0, 0, ax, ay);
    const std::string spec = std::to_string(ax) + "," + std::to_string(ay) + "," +
                             std::to_string(1 / layout.metres_per_pixel()) + ",32,0.5,5,60,110,128,512";
    CHECK_THROWS_WITH(load_compare_image(prefix + "_viridis.png", 0, spec), Catch::Contains("not gray"));
    const std::string meta = frame_metadata(v, *f).dump();
    test::write_file_bytes(prefix + "_viridis.json", Bytes(meta.begin(), meta.end()));
    CHECK_THROWS_WITH(load_compare_image(prefix + "_viridis.png", 0), Catch::Contains("display.colormap"));
}

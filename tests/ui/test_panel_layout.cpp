// The sonar panel's layout at wide and narrow fields of view: the fan fills the panel, every label lies
// outside the fan and off the colour bar, inside the panel, and no two overlap; the layout check sees text
// over the image or the colour bar; the colour bar's title names what is shown.
#include "ui/model/layout.hpp"
#include "ui/model/panel_layout.hpp"
#include "ui/model/text_layout.hpp"

#include "core/scene/scene_io.hpp"

#include <catch2/catch.hpp>

using namespace sonarsim;
using namespace sonarsim::ui;

namespace {

TextRun run_of(const Rect& r) {
    TextRun t;
    t.box = r, t.list_name = "Sonar image", t.glyphs = 3;
    return t;
}

SonarPanelLayout layout_at(double fov_deg, const Rect& panel, bool polar = false) {
    SceneDesc s = default_scene();
    s.sonar.azimuth_fov_deg = fov_deg;
    s.sonar.range_max_m = 12, s.sonar.range_min_m = 0.5;
    return sonar_panel_layout(panel, {s.sonar, 70, 125, colorbar_title(s), polar}, TextMetrics{});
}

} // namespace

TEST_CASE("at 130 and 30 deg the labels keep off the fan, the colour bar and each other", "[ui][panel]") {
    for (double fov : {130.0, 30.0, 90.0, 180.0, 5.0}) {
        for (bool polar : {false, true}) {
            CAPTURE(fov, polar);
            SceneDesc s = default_scene();
            s.sonar.azimuth_fov_deg = fov;
            const ViewerLayout V = viewer_layout(1600, 1000, 1.0f, fan_aspect(s.sonar));
            const SonarPanelLayout L = layout_at(fov, V.sonar, polar);
            std::vector<TextRun> runs;
            for (const auto* list : {&L.bearings, &L.ranges, &L.colorbar_ticks})
                for (const PanelLabel& l : *list) runs.push_back(run_of(l.box));
            runs.push_back(run_of(L.colorbar_title.box));
            CHECK(L.bearings.size() >= (fov >= 30 ? 3u : 2u));
            CHECK(L.ranges.size() >= 3);
            const std::vector<KeepOut> keep = {
                {"sonar image", L.image, polar ? std::nullopt : std::optional(L.fan)},
                {"colour bar", L.colorbar, std::nullopt}};
            CHECK(layout_problems(runs, 1600, 1000, keep).empty());
            for (const TextRun& r : runs) { // inside the panel, above the A-scan
                CHECK(r.box.x >= V.sonar.x);
                CHECK(r.box.x + r.box.w <= V.sonar.x + V.sonar.w);
                CHECK(r.box.y >= L.readout.y + L.readout.h);
                CHECK(r.box.y + r.box.h <= L.ascan.y);
            }
            CHECK(L.ascan.h >= 150);
        }
    }
}

TEST_CASE("the fan fills its panel: as wide as the labels allow, or as tall as the A-scan allows",
          "[ui][panel]") {
    SceneDesc s = default_scene();
    s.sonar.azimuth_fov_deg = 130;
    const ViewerLayout wide = viewer_layout(1600, 1000, 1.0f, fan_aspect(s.sonar));
    const SonarPanelLayout L130 = layout_at(130, wide.sonar);
    CHECK(wide.sonar.w >= 700); // a wide fan widens the panel
    CHECK(wide.view3d.w >= 0.3f * 1600);
    CHECK(L130.image.w >= 0.75f * wide.sonar.w);
    CHECK(L130.image.h >= 300);
    // Every 20 deg bearing, the extremes (+-60) and +-40 included.
    for (double a : {-60.0, -40.0, -20.0, 0.0, 20.0, 40.0, 60.0})
        CHECK(std::count(L130.bearing_deg.begin(), L130.bearing_deg.end(), a) == 1);

    // At 1280 x 800 too: the side bearings sit above the arc's ends, so the fan takes the panel's width
    // (it was 68 % of it with the +-60 deg labels beside the fan), and the 10 m ring keeps its label.
    const ViewerLayout small = viewer_layout(1280, 800, 1.0f, fan_aspect(s.sonar));
    const SonarPanelLayout S130 = layout_at(130, small.sonar);
    CHECK(S130.image.w >= 0.8f * small.sonar.w);
    for (double a : {-60.0, 0.0, 60.0})
        CHECK(std::count(S130.bearing_deg.begin(), S130.bearing_deg.end(), a) == 1);
    CHECK(std::count(S130.range_m.begin(), S130.range_m.end(), 10.0) == 1);

    s.sonar.azimuth_fov_deg = 30;
    const ViewerLayout narrow = viewer_layout(1600, 1000, 1.0f, fan_aspect(s.sonar));
    const SonarPanelLayout L30 = layout_at(30, narrow.sonar);
    CHECK(L30.image.h >= 0.6f * narrow.sonar.h);
    CHECK(L30.ascan.h <= 0.3f * narrow.sonar.h);
}

TEST_CASE("the layout check sees text over the fan and the colour bar, not in the fan's empty corners",
          "[ui][panel]") {
    const SonarPanelLayout L = layout_at(130, {1000, 20, 600, 980});
    const std::vector<KeepOut> keep = {{"sonar image", L.image, L.fan},
                                       {"colour bar", L.colorbar, std::nullopt}};
    const glm::dvec2 mid = L.fan.at(6, 0), corner{L.image.x + 2, L.image.y + L.image.h - 16};
    REQUIRE_FALSE(L.fan.contains(corner.x + 10, corner.y + 6));
    CHECK_FALSE(layout_problems({run_of({float(mid.x), float(mid.y), 40, 13})}, 1600, 1000, keep).empty());
    CHECK(layout_problems({run_of({float(corner.x), float(corner.y), 30, 13})}, 1600, 1000, keep).empty());
    CHECK_FALSE(
        layout_problems({run_of({L.colorbar.x - 10, L.colorbar.y + 40, 30, 13})}, 1600, 1000, keep).empty());
    CHECK(layout_problems({run_of({float(mid.x), float(mid.y), 40, 13})}, 1600, 1000).empty()); // text only
}

TEST_CASE("the colour bar's title names the ideal level or the device's, with TVG and gain", "[ui][panel]") {
    SceneDesc s = default_scene();
    CHECK(colorbar_title(s) == "L_EN dB");
    s.sensor.model = SensorModel::Device;
    s.sensor.tvg = Tvg::Log30;
    s.sensor.gain_db = -12;
    CHECK(colorbar_title(s) == "device level dB (TVG 30 log r, gain -12 dB)");
    s.sensor.tvg = Tvg::Off;
    s.sensor.gain_db = 0;
    CHECK(colorbar_title(s) == "device level dB (no TVG, gain +0 dB)");
}

TEST_CASE("the fan is formed as high as it is shown, in steps of 64 px, never above one row per bin",
          "[ui][layout]") {
    SonarParams s;
    s.beams = 512, s.azimuth_fov_deg = 130, s.range_min_m = 1, s.range_max_m = 120, s.range_bins = 1500;
    const std::shared_ptr<const SonarGrid> g_ptr =
        sonar_grid(s);           // held: the registry keeps only what someone holds
    const SonarGrid& g = *g_ptr; // one row per bin: 1500 px
    REQUIRE(g.default_fan_height_px() == 1500);
    CHECK(fan_height_to_form(190, g) == 256); // at least 256
    CHECK(fan_height_to_form(256, g) == 256);
    CHECK(fan_height_to_form(257, g) == 320);
    CHECK(fan_height_to_form(700.5, g) == 704);
    CHECK(fan_height_to_form(1440, g) == 1472);
    CHECK(fan_height_to_form(1473, g) == 0); // 1536 would pass the full fan: the full fan
    CHECK(fan_height_to_form(4000, g) == 0);
    s.range_bins = 200; // a full fan of 256 px (its least): nothing smaller is formed
    CHECK(fan_height_to_form(100, *sonar_grid(s)) == 0);
}

TEST_CASE("an asymmetric beam-table fan is drawn and labelled between its own edges", "[ui][panel]") {
    // The DIDSON's table (didson300_hf_96.csv): beam centres -14.72 ... +14.09 deg, edges -14.836 ... +14.219
    // (starboard ... port), where a symmetric fan of its width would span +-14.528.
    SceneDesc s = default_scene();
    apply_setting(s, "sonar.device", "didson300-hf", "test");
    REQUIRE(s.sonar.beam_table != "uniform");
    const ViewerLayout V = viewer_layout(1600, 1000, 1.0f, fan_aspect(s.sonar));
    const SonarPanelLayout L =
        sonar_panel_layout(V.sonar, {s.sonar, 70, 125, colorbar_title(s)}, TextMetrics{});
    CHECK(L.fan.port_deg == Approx(14.219189).margin(1e-5));
    CHECK(L.fan.starboard_deg == Approx(-14.836324).margin(1e-5));
    const double r = 0.5 * (s.sonar.range_min_m + s.sonar.range_max_m);
    auto inside = [&](double a_deg) {
        const glm::dvec2 p = L.fan.at(r, a_deg);
        return L.fan.contains(p.x, p.y);
    };
    CHECK(inside(14.1));
    CHECK_FALSE(inside(14.4)); // beyond the port edge, inside a symmetric fan
    CHECK(inside(-14.7));      // inside the starboard edge, outside a symmetric fan
    CHECK_FALSE(inside(-14.9));
    for (double a : L.bearing_deg) { // every bearing label within the fan's own edges
        CHECK(a <= L.fan.port_deg + 1e-9);
        CHECK(a >= L.fan.starboard_deg - 1e-9);
    }
    REQUIRE_FALSE(L.ranges.empty()); // range labels beside the port edge, outside the fan
    for (const PanelLabel& l : L.ranges)
        CHECK_FALSE(L.fan.contains(l.box.x + l.box.w / 2, l.box.y + l.box.h / 2));
}

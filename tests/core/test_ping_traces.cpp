// Kept ping hits (PingTraces): a change of shading re-shades the pings traced before and traces no ray, with
// the bytes a fresh series has; what moves the sonar or the scene traces again; a still sonar's pings share
// one trace per channel; the budget bounds what is kept.
#include "core/kinds/kind_images.hpp"
#include "core/kinds/ping_series.hpp"
#include "core/scene/params.hpp"
#include "core/scene/scene_io.hpp"
#include "core/shading/physics.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>

#include <catch2/catch.hpp>

using namespace sonarsim;

namespace {

/// A side-scan 5 m over sand with a box on its starboard side, moving at `speed_mps` along x.
SceneDesc moving_sidescan(double speed_mps, int pings = 6) {
    SceneDesc s;
    apply_setting(s, "sonar.kind", "sidescan", "test");
    s.sonar.pose = {{0, 0, 5}, {0, 0, 0}};
    s.sonar.azimuth_fov_deg = 1.0, s.sonar.elevation_fov_deg = 60;
    s.sonar.range_min_m = 0.5, s.sonar.range_max_m = 20, s.sonar.range_bins = 300;
    s.sonar.velocity_mps = {speed_mps, 0, 0};
    s.sidescan.pings = pings;
    s.seafloor = Seafloor{};
    s.seafloor->material.nu_db = -30;
    ObjectDesc box;
    box.box_m = {1, 1, 1}, box.position_m = {0.2, -8, 0.5};
    box.material.nu_db = -15;
    s.objects = {box};
    apply_setting(s, "sensor.model", "device", "test");
    validate_scene(s, "test");
    return s;
}

void check_same_series(const PingSeries& a, const PingSeries& b) {
    CHECK(a.level_db == b.level_db);
    CHECK(a.ideal_db == b.ideal_db);
}

} // namespace

TEST_CASE("kept pings: a shading change traces no ray and gives a fresh series' bytes, a move traces again",
          "[kinds][traces]") {
    const SceneDesc s = moving_sidescan(1.0);
    PingTraces traces;
    const PingSeries first = render_pings(s, {}, &traces);
    REQUIRE(first.rays_traced > 0);
    CHECK(traces.kept_pings() == size_t(first.pings * first.channels));
    CHECK(traces.kept_bytes() > 0);

    for (const auto& [key, value] : std::vector<std::pair<std::string, double>>{
             {"sonar.source_level_db", 200}, {"sonar.noise_level_db", 60}, {"sensor.gain_db", 12}}) {
        SECTION(key) {
            SceneDesc changed = s;
            apply_setting(changed, key, value, "test");
            REQUIRE(changed_stage(s, changed) >= Stage::Shade);
            const PingSeries again = render_pings(changed, {}, &traces);
            CHECK(again.rays_traced == 0);
            CHECK(again.traced_profiles == 0);
            CHECK(again.shaded_profiles == first.pings * first.channels);
            CHECK(again.level_db != first.level_db);
            check_same_series(again, render_pings(changed));
        }
    }
    SECTION("a material's value the adaptive sampler steers by: a preview re-shades, a full series traces") {
        SceneDesc changed = s;
        apply_setting(changed, "objects.0.material.nu_db", -5.0, "test");
        REQUIRE(changed_stage(s, changed) == Stage::Place);
        PingControl preview;
        preview.preview = true;
        const PingSeries quick = render_pings(changed, preview, &traces);
        CHECK(quick.rays_traced == 0);
        CHECK(quick.ideal_db != first.ideal_db);
        const PingSeries full = render_pings(changed, {}, &traces);
        CHECK(full.rays_traced > 0);
        check_same_series(full, render_pings(changed));
    }
    SECTION(
        "a value the sampler steers by, keep_placement: a full series keeps the pings whose estimate made "
        "anew meets the tolerances") {
        // The viewer's: the pings' traces keep their estimate cells, a change re-shades them and estimates
        // them anew; a ping is traced again only where that estimate misses.
        PingControl keep;
        keep.keep_placement = true;
        PingTraces kept;
        const PingSeries placed = render_pings(s, keep, &kept);
        check_same_series(placed, first); // keeping the estimate cells changes no byte
        SceneDesc changed = s;
        apply_setting(changed, "seafloor.material.nu_db", -27.0, "test");
        apply_setting(changed, "objects.0.material.nu_db", -13.0, "test");
        apply_setting(changed, "sonar.frequency_khz", s.sonar.frequency_khz * 1.1, "test"); // same pings
        REQUIRE(changed_stage(s, changed) == Stage::Place);
        const PingSeries same_rays = render_pings(changed, keep, &kept);
        CHECK(same_rays.rays_traced == 0);
        CHECK(same_rays.traced_profiles == 0);
        CHECK(same_rays.kept_placement_profiles == first.pings * first.channels);
        // Each profile is the kept hits shaded with the new values: the preview's bytes, shaded alike.
        PingTraces for_preview;
        render_pings(s, keep, &for_preview);
        PingControl preview = keep;
        preview.preview = true;
        check_same_series(same_rays, render_pings(changed, preview, &for_preview));
        // Within the tolerances of a series traced anew.
        const PingSeries fresh = render_pings(changed);
        double num = 0, den = 0;
        for (size_t k = 0; k < fresh.ideal_db.size(); ++k) {
            const double a =
                std::isfinite(same_rays.ideal_db[k]) ? std::pow(10.0, same_rays.ideal_db[k] / 10) : 0;
            const double b = std::isfinite(fresh.ideal_db[k]) ? std::pow(10.0, fresh.ideal_db[k] / 10) : 0;
            num += std::abs(a - b), den += b;
        }
        CHECK(num / den < changed.sampling.tolerance_rel_l1);

        // The box 18 dB louder: the starboard channel, which sees it, misses with cells placed for a faint
        // box (1.1 % estimated anew against 0.28 % as traced) and is traced again; the port channel is kept.
        SceneDesc louder = changed;
        apply_setting(louder, "objects.0.material.nu_db", 5.0, "test");
        REQUIRE(changed_stage(changed, louder) == Stage::Place);
        const PingSeries relobed = render_pings(louder, keep, &kept);
        CHECK(relobed.traced_profiles > 0); // the pings that see the box
        CHECK(relobed.rays_traced > 0);
        CHECK(relobed.traced_profiles + relobed.shaded_profiles == first.pings * first.channels);
        CHECK(relobed.kept_placement_profiles == relobed.shaded_profiles);

        // The viewer's way: a drag's preview re-shades the kept hits; the full series at rest then copies
        // its levels (the same hits shaded alike) where the estimate made anew from them meets, and traces
        // the rest.
        PingTraces dragged; // as `kept`: placed for s, kept through `changed`
        render_pings(s, keep, &dragged);
        render_pings(changed, keep, &dragged);
        const PingSeries quick = render_pings(louder, preview, &dragged);
        CHECK(quick.rays_traced == 0);
        const PingSeries rest = render_pings(louder, keep, &dragged);
        CHECK(rest.copied_profiles == relobed.kept_placement_profiles); // nothing shaded again
        CHECK(rest.kept_placement_profiles == relobed.kept_placement_profiles);
        CHECK(rest.traced_profiles == relobed.traced_profiles);
        CHECK(rest.rays_traced == relobed.rays_traced);
        check_same_series(rest, relobed);
    }
    SECTION("the sonar moved: every ping from a new pose traces; the same bytes as a fresh series") {
        SceneDesc moved = s;
        moved.sonar.pose.position_m[0] += 0.5;
        const PingSeries again = render_pings(moved, {}, &traces);
        CHECK(again.rays_traced > 0);
        check_same_series(again, render_pings(moved));
    }
    SECTION("an object moved: the geometry changed, every ping traces") {
        SceneDesc moved = s;
        moved.objects[0].position_m[1] = -6;
        const PingSeries again = render_pings(moved, {}, &traces);
        CHECK(again.rays_traced > first.rays_traced / 2);
        check_same_series(again, render_pings(moved));
    }
}

TEST_CASE("a still side-scan's pings share one trace per channel, a moving one's each trace",
          "[kinds][traces]") {
    const PingSeries one = render_pings(moving_sidescan(0.0, 1));
    const PingSeries still = render_pings(moving_sidescan(0.0, 8));
    CHECK(still.rays_traced == one.rays_traced);
    CHECK(still.traced_profiles == 2);
    CHECK(still.shaded_profiles == 14);
    CHECK(still.copied_profiles == 0);
    const size_t n = size_t(still.channels) * size_t(still.bins);
    CHECK(std::equal(one.ideal_db.begin(), one.ideal_db.end(), still.ideal_db.begin() + long(7 * n)));
    const PingSeries moving = render_pings(moving_sidescan(1.0, 8));
    CHECK(moving.rays_traced > 4 * one.rays_traced);
}

TEST_CASE("kept pings stay within their budget, a ping that does not fit traces again", "[kinds][traces]") {
    const SceneDesc s = moving_sidescan(1.0, 4);
    PingTraces none(0);
    const PingSeries first = render_pings(s, {}, &none);
    CHECK(none.kept_pings() == 0);
    CHECK(none.kept_bytes() == 0);
    SceneDesc louder = s;
    louder.sonar.source_level_db += 3;
    CHECK(render_pings(louder, {}, &none).rays_traced == first.rays_traced);

    PingTraces all;
    render_pings(s, {}, &all);
    PingTraces some(all.kept_bytes() / 2);
    render_pings(s, {}, &some);
    CHECK(some.kept_pings() > 0);
    CHECK(some.kept_pings() < all.kept_pings());
    CHECK(some.kept_bytes() <= some.budget_bytes());
    const PingSeries again = render_pings(louder, {}, &some);
    CHECK(again.rays_traced > 0);
    CHECK(again.rays_traced < first.rays_traced);
    check_same_series(again, render_pings(louder));
}

TEST_CASE("pings along a played trajectory: ping k at k dt from the track's pose then, the newest at now",
          "[kinds][traces]") {
    SceneDesc s = moving_sidescan(0.0, 5);
    const Trajectory line = {{2.0, {{0, 0, 5}, {0, 0, 0}}},
                             {12.0, {{10, 0, 5}, {0, 0, 0}}}}; // 1 m/s from t 2 s
    const double dt = kind_ping_interval_s(s, sound_speed_m_s(s.water.temperature_c, s.water.depth_m));
    const double now = 2.0 + 3.3;
    const auto pings = ping_schedule_along(s, line, now);
    REQUIRE(pings.size() == 5);
    const auto newest = std::int64_t(std::floor(3.3 / dt));
    for (size_t i = 0; i < pings.size(); ++i) {
        const std::int64_t k = newest - 4 + std::int64_t(i);
        CHECK(pings[i].number == k);
        CHECK(pings[i].time_s == Approx(double(k) * dt).epsilon(1e-12));
        CHECK(pings[i].vehicle.position_m[0] == Approx(double(k) * dt).epsilon(1e-9));
    }
    CHECK(pings.back().time_s <= 3.3);
    CHECK(pings.back().time_s + dt > 3.3);
    // Before the track's start every ping is heard from its first pose, each with its own noise draw.
    const auto early = ping_schedule_along(s, line, 1.0);
    for (const Ping& p : early) {
        CHECK(p.number < 0);
        CHECK(p.vehicle.position_m[0] == 0);
        CHECK(ping_noise_draw(p.number) != 0);
    }
    CHECK(ping_noise_draw(-1) != ping_noise_draw(-2));

    SceneDesc scan;
    apply_setting(scan, "sonar.device", "ping360", "test");
    scan.scanning.sector_start_deg = -60, scan.scanning.sector_end_deg = 60, scan.scanning.step_deg = 30;
    validate_scene(scan, "test");
    const auto steps = ping_schedule_along(scan, line, 7.0);
    REQUIRE(steps.size() == 5);
    for (const Ping& p : steps) CHECK(p.head_deg == -60 + 30 * double(((p.number % 5) + 5) % 5));
}

TEST_CASE(
    "a waterfall scrolling along a played trajectory traces only its new pings and keeps the others' bytes",
    "[kinds][traces]") {
    const SceneDesc s = moving_sidescan(0.0, 12);
    const Trajectory line = {{0.0, {{-2, 0, 5}, {0, 0, 0}}}, {5.0, {{8, 0, 5}, {0, 0, 0}}}};
    const double dt = kind_ping_interval_s(s, sound_speed_m_s(s.water.temperature_c, s.water.depth_m));
    PingTraces traces;
    PingControl at;
    at.schedule = ping_schedule_along(s, line, 1.0);
    const PingSeries before = render_pings(s, at, &traces);
    at.schedule = ping_schedule_along(s, line, 1.0 + 3 * dt);
    REQUIRE(at.schedule.front().number == before.schedule[3].number);
    const PingSeries after = render_pings(s, at, &traces);
    // The nine pings both hold are copied: the same bytes, three rows down the series.
    const size_t row = size_t(after.channels) * size_t(after.bins);
    CHECK(std::equal(before.level_db.begin() + long(3 * row), before.level_db.end(), after.level_db.begin()));
    // Only the three new pings traced, and the series is what a fresh one is.
    PingControl fresh_control;
    fresh_control.schedule = at.schedule;
    const PingSeries fresh = render_pings(s, fresh_control);
    check_same_series(after, fresh);
    CHECK(after.rays_traced > 0);
    CHECK(after.rays_traced < fresh.rays_traced / 3);
    CHECK(after.traced_profiles == 6); // three new pings, two channels
    CHECK(after.copied_profiles == 18);
    CHECK(after.shaded_profiles == 0);
}

TEST_CASE("a sector scan's sweep along a still trajectory, wrapped past its sector's end, is the scene's own "
          "sweep",
          "[kinds][traces]") {
    SceneDesc s;
    apply_setting(s, "sonar.kind", "scanning", "test");
    s.sonar.pose = {{0, 0, 2}, {0, 20, 0}};
    s.sonar.range_min_m = 0.5, s.sonar.range_max_m = 12, s.sonar.range_bins = 200;
    s.scanning.sector_start_deg = -60, s.scanning.sector_end_deg = 60, s.scanning.step_deg = 30;
    s.seafloor = Seafloor{};
    ObjectDesc box;
    box.box_m = {1, 1, 1}, box.position_m = {6, 3, 0.5};
    s.objects = {box};
    validate_scene(s, "test");
    const double dt = kind_ping_interval_s(s, sound_speed_m_s(s.water.temperature_c, s.water.depth_m));
    const Trajectory still = {{0.0, s.sonar.pose}, {100.0, s.sonar.pose}};
    PingControl along;
    along.schedule = ping_schedule_along(s, still, 7.2 * dt); // counts 3 ... 7: steps 3, 4, 0, 1, 2
    REQUIRE(along.schedule.front().number == 3);
    const PingSeries own = render_pings(s), wrapped = render_pings(s, along);
    CHECK(wrapped.profile(2, 0)[0] == own.profile(0, 0)[0]);
    DisplayParams d;
    d.lo_db = 20, d.hi_db = 90;
    const Image8 a = sweep_image(own, d, s.sonar.range_max_m, 96),
                 b = sweep_image(wrapped, d, s.sonar.range_max_m, 96);
    CHECK(a.pixels == b.pixels);
    size_t lit = 0; // the box and floor echo in the sweep: not an empty picture
    for (size_t i = 0; i < a.pixels.size(); i += 3) lit += a.pixels[i] > 0;
    CHECK(lit > a.pixels.size() / 3 / 20);
}

TEST_CASE("kept levels are only copied into a series of the scene they were made with, a drag there and back "
          "included",
          "[kinds][traces]") {
    const SceneDesc s = moving_sidescan(1.0, 4);
    PingTraces traces;
    const PingSeries first = render_pings(s, {}, &traces);
    PingControl preview;
    preview.preview = true;
    SceneDesc brighter = s;
    apply_setting(brighter, "objects.0.material.nu_db", -5.0, "test");
    const PingSeries there = render_pings(brighter, preview, &traces); // the hits placed for s, re-shaded
    CHECK(there.rays_traced == 0);
    CHECK(there.ideal_db != first.ideal_db);
    const PingSeries back = render_pings(s, preview, &traces); // s's own hits and shading: first's bytes
    CHECK(back.rays_traced == 0);
    check_same_series(back, first);
    const PingSeries again = render_pings(s, {}, &traces); // copied: nothing but the scene itself
    CHECK(again.rays_traced == 0);
    check_same_series(again, first);
}

TEST_CASE("a cancelled series keeps the traces it finished, so the next one traces only the rest",
          "[kinds][traces]") {
    const SceneDesc s = moving_sidescan(1.0, 12);
    const PingSeries fresh = render_pings(s);
    PingTraces traces;
    std::atomic<bool> cancel{false};
    PingControl control;
    control.cancel = &cancel;
    control.progress = [&](int done, int) {
        if (done >= 4) cancel = true; // four pings' channels traced
    };
    CHECK_THROWS_AS(render_pings(s, control, &traces), TraceCancelled);
    const auto finished = int(traces.kept_pings());
    CHECK(finished >= 8);
    CHECK(finished < 24);
    const PingSeries rest = render_pings(s, {}, &traces);
    CHECK(rest.traced_profiles == 24 - finished);
    CHECK(rest.rays_traced < fresh.rays_traced);
    check_same_series(rest, fresh);
}

TEST_CASE("a display value keeps the kept levels: the series is copied", "[kinds][traces]") {
    const SceneDesc s = moving_sidescan(1.0, 4);
    PingTraces traces;
    const PingSeries first = render_pings(s, {}, &traces);
    SceneDesc shown = s;
    apply_setting(shown, "display.colormap", "viridis", "test");
    REQUIRE(changed_stage(s, shown) == Stage::Display);
    const PingSeries again = render_pings(shown, {}, &traces);
    CHECK(again.copied_profiles == first.pings * first.channels);
    CHECK(again.rays_traced == 0);
    check_same_series(again, first);
}

TEST_CASE("kept placements of pings: a series of the scene's own bytes places them anew, a cancelled series "
          "leaves them to be estimated, progress counts each profile once",
          "[kinds][traces]") {
    const SceneDesc s = moving_sidescan(1.0);
    PingControl keep;
    keep.keep_placement = true;
    SceneDesc changed = s;
    apply_setting(changed, "seafloor.material.nu_db", -27.0, "test");
    apply_setting(changed, "objects.0.material.nu_db", -13.0, "test");
    apply_setting(changed, "sonar.frequency_khz", s.sonar.frequency_khz * 1.1, "test");
    SceneDesc louder = changed; // the box 18 dB louder: its channel misses with the kept rays
    apply_setting(louder, "objects.0.material.nu_db", 5.0, "test");
    const PingSeries fresh = render_pings(changed);

    // Kept, then asked for without keep_placement (a snapshot, render's bytes): placed anew.
    PingTraces t;
    render_pings(s, keep, &t);
    const PingSeries kept = render_pings(changed, keep, &t);
    CHECK(kept.rays_traced == 0);
    CHECK(kept.kept_placement_profiles == kept.pings * kept.channels);
    CHECK(kept.level_db != fresh.level_db);                     // the kept rays are not the fresh placement
    const PingSeries display = render_pings(changed, keep, &t); // nothing changed: copied, still kept
    CHECK(display.copied_profiles == display.pings * display.channels);
    CHECK(display.kept_placement_profiles == display.pings * display.channels);
    const PingSeries anew = render_pings(changed, {}, &t);
    CHECK(anew.rays_traced > 0);
    CHECK(anew.kept_placement_profiles == 0);
    check_same_series(anew, fresh);

    // The reference: a series that misses on the box's channel and traces it again.
    PingTraces u;
    render_pings(s, keep, &u);
    render_pings(changed, keep, &u);
    const PingSeries missed = render_pings(louder, keep, &u);
    REQUIRE(missed.traced_profiles > 0);
    // Cancelled before any trace, then a preview of a value that does not steer the sampler: the series at
    // rest still estimates the kept rays anew and traces the same pings again.
    PingTraces v;
    render_pings(s, keep, &v);
    render_pings(changed, keep, &v);
    std::atomic<bool> cancel{true};
    PingControl cancelled = keep;
    cancelled.cancel = &cancel;
    CHECK_THROWS_AS(render_pings(louder, cancelled, &v), TraceCancelled);
    SceneDesc gain = louder;
    apply_setting(gain, "sensor.gain_db", 6.0, "test");
    PingControl preview = keep;
    preview.preview = true;
    render_pings(gain, preview, &v);
    std::vector<int> seen;
    PingControl rest_control = keep;
    rest_control.progress = [&](int done, int) { seen.push_back(done); };
    const PingSeries rest = render_pings(gain, rest_control, &v);
    CHECK(rest.traced_profiles == missed.traced_profiles);
    CHECK(rest.kept_placement_profiles == missed.kept_placement_profiles);
    CHECK(rest.ideal_db == missed.ideal_db);
    // Progress: never backwards, the last call all the pings, once.
    REQUIRE_FALSE(seen.empty());
    CHECK(std::is_sorted(seen.begin(), seen.end()));
    CHECK(seen.back() == rest.pings);
    CHECK(std::count(seen.begin(), seen.end(), rest.pings) == 1);
}

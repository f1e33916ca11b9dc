// The viewer's non-GL session: bad values and files keep the last good scene; the worker's newest request
// wins; every slider of the controls panel visibly changes the image.
#include "support.hpp"
#include "core/io/ground_truth_files.hpp"
#include "core/scene/sampling_scheme.hpp"

#include "ui/model/render_worker.hpp"
#include "ui/model/session.hpp"

#include "core/io/output.hpp"
#include "core/io/png.hpp"
#include "core/scene/scene_io.hpp"
#include "core/shading/physics.hpp"

#include <catch2/catch.hpp>
#include <filesystem>
#include <chrono>
#include <cmath>
#include <fstream>

using namespace sonarsim;
using namespace std::chrono_literals;

TEST_CASE("a bad value or file shows an error and keeps the last good scene and image", "[ui][session]") {
    ui::Session session(default_scene());
    session.submit();
    REQUIRE(session.wait_latest(60s));
    REQUIRE(session.shown());
    const auto shown = session.shown_count();

    CHECK_FALSE(session.set("sonar.range_max_m", -3.0));
    CHECK(session.error().find("sonar.range_max_m") != std::string::npos);
    CHECK(session.scene().sonar.range_max_m == 5.0);
    session.clear_error();

    CHECK_FALSE(session.set("sonar.range_min_m", 7.0)); // above range_max: a cross-field error
    CHECK(session.scene().sonar.range_min_m == 0.5);

    const std::string bad = test::ui_out_path("bad_scene.json");
    std::ofstream(bad) << "{\"sonar\": {\"beams\": \"many\"}}";
    CHECK_FALSE(session.open_scene(bad));
    CHECK(session.error().find("sonar.beams") != std::string::npos);
    CHECK_FALSE(session.open_scene(test::ui_out_path("no_such_scene.json")));
    CHECK_FALSE(session.add_mesh(test::ui_out_path("no_such_mesh.obj")));
    CHECK(session.scene().objects.size() == 1);

    CHECK(session.submit() == 0); // nothing changed: nothing to render
    CHECK(session.shown_count() == shown);
}

TEST_CASE("moving an object updates the session geometry in place, a new shape rebuilds it",
          "[ui][session]") {
    ui::Session session(default_scene());
    const std::uint64_t version = session.meshes_version();
    const auto mesh = session.geometry().local_mesh(0);
    REQUIRE(session.set("objects.0.position", json::array({2.0, 1.0, 0.11})));
    CHECK(session.meshes_version() == version); // nothing to upload again: the view places it
    CHECK(session.geometry().local_mesh(0).get() == mesh.get());
    CHECK(session.geometry().object_transform(0)[3][0] == 2.0);
    // Picking sees the object where it now is: straight down onto its top face (0.11 + 0.22 / 2 high).
    const auto hit = session.geometry().intersect({2.0, 1.0, 1.0}, {0, 0, -1}, 10);
    REQUIRE(hit);
    CHECK(hit->t == Approx(1.0 - 0.22).epsilon(1e-6));
    CHECK(hit->material == 1);
    REQUIRE(session.edit([](SceneDesc& s) { (*s.objects[0].box_m)[2] = 0.3; }));
    CHECK(session.meshes_version() != version);
    CHECK(session.geometry().local_mesh(0).get() != mesh.get());
    session.submit();
    REQUIRE(session.wait_latest(60s));
    REQUIRE(session.shown());
    CHECK(session.error().empty());
}

TEST_CASE("the newest request supersedes older ones", "[ui][worker]") {
    ui::RenderWorker worker;
    SceneDesc s = default_scene();
    std::uint64_t last = 0;
    for (int i = 0; i < 12; ++i) {
        s.sonar.pose.orientation_deg[2] = -38.96 + i;
        last = worker.request(s);
    }
    REQUIRE(worker.wait_for(last, 60s));
    auto r = worker.take();
    REQUIRE(r);
    CHECK(r->id == last);
    CHECK(r->error.empty());
    CHECK(r->scene.sonar.pose.orientation_deg[2] == Approx(-38.96 + 11));
    CHECK_FALSE(worker.take()); // taken once
}

TEST_CASE("a mesh the worker cannot load is reported and the old geometry stays", "[ui][worker]") {
    ui::RenderWorker worker;
    SceneDesc s = default_scene();
    set_scheme(s.sampling, SamplingScheme::Spread); // every physics change re-shades
    auto id = worker.request(s);
    REQUIRE(worker.wait_for(id, 60s));
    REQUIRE(worker.take()->frame);
    ObjectDesc o;
    o.mesh = o.mesh_resolved = test::ui_out_path("missing.stl");
    s.objects.push_back(o);
    id = worker.request(s);
    REQUIRE(worker.wait_for(id, 60s));
    auto r = worker.take();
    REQUIRE(r);
    CHECK_FALSE(r->frame);
    CHECK(r->error.find("missing.stl") != std::string::npos);
    s.objects.pop_back();
    s.sonar.noise_level_db = 12;
    id = worker.request(s);
    REQUIRE(worker.wait_for(id, 60s));
    r = worker.take();
    REQUIRE(r);
    CHECK(r->frame);
    CHECK(r->stage == Stage::Shade);
    set_scheme(s.sampling, SamplingScheme::Adaptive);
    s.sonar.noise_level_db = 14;
    id = worker.request(s);
    REQUIRE(worker.wait_for(id, 60s));
    CHECK(worker.take()->stage == Stage::Trace);
    s.water.temperature_c = 16; // adaptive rays follow how the level varies: a full image re-traces
    id = worker.request(s);
    REQUIRE(worker.wait_for(id, 60s));
    r = worker.take();
    CHECK(r->stage == Stage::Place);
    CHECK_FALSE(r->frame->preview());
}

TEST_CASE("every slider visibly changes the image", "[ui][params]") {
    const SceneDesc base = default_scene();
    auto image = [](const SceneDesc& s) {
        Simulator sim(s);
        return encode_png(sim.render()->sector());
    };
    const Bytes ref = image(base);
    for (const ParamSpec& p : scene_params()) {
        if (p.type != ParamType::Number && p.type != ParamType::Integer) continue;
        // The adaptive sampler's accuracy target: in this scene it refines the same way for every value on
        // the slider (its effect is on the error estimate, not visible here).
        // Likewise its ray budget: this scene never reaches it.
        if (p.key == "sampling.tolerance_db" || p.key == "sampling.tolerance_rel_l1" ||
            p.key == "sampling.max_rays")
            continue;
        // The pings that build a frame only show while the sonar moves (and must divide the beams).
        if (p.key == "sonar.pings_per_frame") continue;
        // The rows of the side-scan and scanning sonars change their images (tests/core/test_kinds.cpp).
        if (!p.used_by(SonarKind::Imaging)) continue;
        // Rows that recompute nothing (the 8-bit exports' mapping, export.*) are no image's business.
        if (p.stage == Stage::None) continue;
        const SliderRange r = p.slider_range();
        SceneDesc before = base;
        if (p.key.rfind("sensor.", 0) == 0) { // sensor parameters act once the device sensor is on
            apply_setting(before, "sensor.model", "device", "test");
            before.display.auto_range = false; // which would hide the gain
            if (p.key == "sensor.taylor_sidelobe_db") before.sensor.azimuth_window = AzimuthWindow::Taylor;
            if (p.key == "sensor.speckle_k_shape") before.sensor.speckle = Speckle::K;
        }
        // Multipath: the floor a mirror, so that rays it reflects reach the water surface 0.6 m above the
        // sonar, and two bounces, so that paths reflect on the surface (its roughness shows).
        const bool multipath = p.key.rfind("water.surface", 0) == 0 || p.key == "sampling.bounces";
        if (multipath) {
            before.water.surface_height_m = before.sonar.pose.position_m[2] + 0.6;
            before.seafloor->material.reflection_db = 3;
            before.sampling.bounces = p.key == "sampling.bounces" ? 0 : 2;
            // Long paths: a wider window, little absorption, a surface that echoes well.
            before.sonar.range_max_m = 12, before.sonar.frequency_khz = 900;
            before.water.surface_material.nu_db = -20;
        }
        const Bytes ref_before = p.key.rfind("sensor.", 0) == 0 || multipath ? image(before) : ref;
        const double v0 = p.get(before).get<double>();
        double v = v0 + 0.2 * (r.hi - r.lo);
        if (v > r.hi) v = v0 - 0.2 * (r.hi - r.lo);
        if (p.key == "sampling.bounces") v = 1;
        if (p.key == "sonar.range_min_m") v = 1.0;
        if (p.key == "display.lo_db") v = 95.0; // stays below hi_db
        SceneDesc after = before;
        apply_setting(after, p.key, p.type == ParamType::Integer ? json(int(v)) : json(v), "test");
        validate_scene(after, "test");
        INFO(p.key << ": " << v0 << " -> " << v);
        const bool changed = image(after) != ref_before;
        CHECK(changed);
    }
    // Materials of the prism. The specular term shows on its faces (seen at 30-60 deg incidence) once its
    // lobe is wide; h matters only where mu > 0.
    for (const MaterialSpec& m : material_params()) {
        const SliderRange r = m.slider_range();
        SceneDesc before = base;
        before.objects[0].material.h_deg = 30;
        if (m.key == "h_deg") before.objects[0].material.mu = 1e-4;
        if (m.key == "reflection_db") // the prism a mirror: its reflections reach the floor
            before.objects[0].material.reflection_db = 3, before.sampling.bounces = 1;
        // The texture's shape shows once it is on.
        if (m.key == "texture_correlation_m") before.objects[0].material.texture_rms_db = 3;
        if (m.key == "ripple_wavelength_m" || m.key == "ripple_direction_deg")
            before.objects[0].material.ripple_amplitude_db = 2;
        SceneDesc after = before;
        after.objects[0].material.*(m.field) += 0.2 * (r.hi - r.lo);
        INFO("objects.0.material." << m.key);
        const bool changed = image(after) != image(before);
        CHECK(changed);
    }
}

TEST_CASE("a drag renders previews, then the full image once the input rests", "[ui][session]") {
    ui::Session session(default_scene());
    session.submit();
    REQUIRE(session.wait_latest(60s));
    REQUIRE_FALSE(session.shown()->frame->preview());

    // Dragging: each change goes as a preview.
    const auto t0 = ui::Session::Clock::now();
    REQUIRE(session.edit([](SceneDesc& s) { s.sonar.pose.orientation_deg[2] = -36.0; }));
    REQUIRE(session.submit(true, t0) != 0);
    REQUIRE(session.wait_latest(60s));
    const auto* shown = session.shown();
    REQUIRE(shown->frame->preview());
    CHECK(shown->scene.sonar.pose.orientation_deg[2] == -36.0);
    CHECK(session.full_pending());
    CHECK(session.busy());
    // Held still but not for long: nothing new; rested: the same scene again, in full quality.
    CHECK(session.submit(true, t0 + ui::Session::kRest / 3) == 0);
    REQUIRE(session.submit(true, t0 + ui::Session::kRest) != 0);
    REQUIRE(session.wait_latest(60s));
    CHECK_FALSE(session.shown()->frame->preview());
    CHECK(session.shown()->scene.sonar.pose.orientation_deg[2] == -36.0);
    CHECK_FALSE(session.full_pending());
    CHECK(session.submit(true, t0 + 10 * ui::Session::kRest) == 0); // nothing more to do

    // Released right after a change: the full image is requested at once.
    const auto t1 = ui::Session::Clock::now();
    REQUIRE(session.edit([](SceneDesc& s) { s.sonar.pose.orientation_deg[2] = -35.0; }));
    REQUIRE(session.submit(true, t1) != 0);
    REQUIRE(session.submit(false, t1) != 0);
    REQUIRE(session.wait_latest(60s));
    CHECK_FALSE(session.shown()->frame->preview());

    // A snapshot taken while a preview is on screen writes the full image.
    REQUIRE(session.edit([](SceneDesc& s) { s.sonar.pose.orientation_deg[2] = -34.0; }));
    REQUIRE(session.submit(true) != 0);
    REQUIRE(session.wait_latest(60s));
    REQUIRE(session.shown()->frame->preview());
    const std::string prefix = test::ui_out_path("after_preview");
    REQUIRE(session.snapshot(prefix, {}));
    CHECK_FALSE(session.shown()->frame->preview());
    Simulator fresh(session.scene());
    CHECK(test::read_bytes(prefix + ".npy") == encode_npy(fresh.render()->polar()));
    // The status says where the files went and names each one by what it adds to the prefix.
    const std::filesystem::path named = std::filesystem::absolute(prefix).lexically_normal();
    CHECK(session.status() == "snapshot " + named.filename().string() + " in " +
                                  named.parent_path().string() + ": .png _polar.png .npy .json _scene.json");
    for (const char* suffix : {".png", "_polar.png", ".npy", ".json", "_scene.json"})
        CHECK(std::filesystem::is_regular_file(prefix + suffix));

    // A slider that steers the sampler keeps the rays (re-shaded, no ray traced); a snapshot of that image
    // writes what `render` makes of its scene all the same: rays placed anew.
    REQUIRE(session.edit([](SceneDesc& s) { s.water.temperature_c = 19.5; }));
    REQUIRE(session.submit() != 0);
    REQUIRE(session.wait_latest(60s));
    REQUIRE(session.shown()->frame->placement_kept);
    const std::string kept_prefix = test::ui_out_path("after_kept_placement");
    REQUIRE(session.snapshot(kept_prefix, {}));
    CHECK_FALSE(session.shown()->frame->placement_kept);
    CHECK(test::read_bytes(kept_prefix + ".npy") == encode_npy(Simulator(session.scene()).render()->polar()));

    // The viewer's S key reads the annotated PNG back from the screen, so it first asks for the image placed
    // anew (once per kept image, however many frames ask) and draws it before the snapshot is taken.
    for (const double t_c : {19.0, 18.5}) { // the first traces again (the snapshot's rays kept no estimate)
        REQUIRE(session.edit([&](SceneDesc& s) { s.water.temperature_c = t_c; }));
        REQUIRE(session.submit() != 0);
        REQUIRE(session.wait_latest(60s));
    }
    REQUIRE(session.shown_kept_placement());
    const std::uint64_t kept_count = session.shown_count();
    const std::uint64_t before = session.requested_id();
    CHECK(session.place_anew());
    const std::uint64_t asked = session.requested_id();
    CHECK(asked > before);
    CHECK(session.place_anew()); // asked already: on its way, not asked again
    CHECK(session.requested_id() == asked);
    REQUIRE(session.wait_latest(60s));
    CHECK(session.shown_count() == kept_count + 1); // one image more: the one placed anew
    CHECK_FALSE(session.shown_kept_placement());
    CHECK_FALSE(session.place_anew()); // nothing kept on screen: nothing to ask
    CHECK(encode_npy(session.shown()->frame->polar()) ==
          encode_npy(Simulator(session.scene()).render()->polar()));

    // A kept image with a newer edit on its way: that edit's image comes next, nothing is asked.
    for (const double t_c : {18.0, 17.5}) {
        REQUIRE(session.edit([&](SceneDesc& s) { s.water.temperature_c = t_c; }));
        REQUIRE(session.submit() != 0);
        REQUIRE(session.wait_latest(60s));
    }
    REQUIRE(session.shown_kept_placement());
    REQUIRE(session.edit([](SceneDesc& s) { s.water.temperature_c = 17.0; }));
    const std::uint64_t edited = session.requested_id();
    CHECK_FALSE(session.place_anew());
    CHECK(session.requested_id() == edited);
}

TEST_CASE("a preview request of a scheme without previews needs no second render", "[ui][session]") {
    SceneDesc s = default_scene();
    set_scheme(s.sampling, SamplingScheme::Spread);
    ui::Session session(s);
    REQUIRE(session.submit(true) != 0);
    REQUIRE(session.wait_latest(60s));
    CHECK_FALSE(session.shown()->frame->preview());
    CHECK_FALSE(session.full_pending());
}

TEST_CASE("with ground truth on the worker adds it to full frames and snapshots write it", "[ui][session]") {
    ui::Session session(default_scene());
    session.submit();
    REQUIRE(session.wait_latest(60s));
    CHECK_FALSE(session.shown()->ground_truth); // only when asked for
    session.set_ground_truth(true);
    REQUIRE(session.submit() != 0); // the shown scene again, with it
    REQUIRE(session.wait_latest(60s));
    const auto* shown = session.shown();
    REQUIRE(shown->ground_truth);
    const GroundTruth expect = compute_ground_truth(shown->frame->hits(), shown->scene);
    CHECK(shown->ground_truth->object_id == expect.object_id);
    const std::string prefix = test::ui_out_path("ground_truth");
    REQUIRE(session.snapshot(prefix, {}));
    for (auto& [path, bytes] : ground_truth_files(prefix, expect)) CHECK(test::read_bytes(path) == bytes);
}

TEST_CASE("the worker forms the fan at the panel's height; snapshots still write the full fan",
          "[ui][session]") {
    ui::Session session(default_scene()); // 512 bins: the full fan is 512 px high
    session.submit();
    REQUIRE(session.wait_latest(60s));
    REQUIRE(session.shown()->frame->sector().height == 512);
    const auto hits = session.shown()->frame->hits_ptr;
    session.set_fan_height_px(320);
    REQUIRE(session.submit() != 0); // the same scene again: its fan only
    REQUIRE(session.wait_latest(60s));
    const Frame& f = *session.shown()->frame;
    CHECK(f.sector().height == 320);
    CHECK(f.hits_ptr == hits);
    const std::string prefix = test::ui_out_path("small_fan");
    REQUIRE(session.snapshot(prefix, {}));
    Simulator fresh(session.scene());
    CHECK(test::read_bytes(prefix + ".png") == encode_png(fresh.render()->sector()));
    session.set_fan_height_px(320);
    CHECK(session.submit() == 0); // unchanged: nothing to do
}

TEST_CASE("the viewer's session shows a side-scan's waterfall and a scan's sweep, and switching the kind "
          "switches the image; snapshots write the kind's files",
          "[ui][session][kinds]") {
    SceneDesc s = default_scene();
    ui::Session session(s);
    session.submit();
    REQUIRE(session.wait_full(60s));
    REQUIRE(session.shown()->frame);
    // To a side-scan: the image is its waterfall, as render_pings makes it (pings x (port | starboard)).
    REQUIRE(session.set("sonar.kind", "sidescan"));
    REQUIRE(session.set("sidescan.pings", 12));
    REQUIRE(session.wait_full(60s));
    const ui::RenderResult* r = session.shown();
    REQUIRE(r);
    CHECK(session.error().empty());
    REQUIRE(r->pings);
    CHECK_FALSE(r->frame);
    CHECK(r->pings->pings == 12);
    CHECK(r->pings->channels == 2);
    const PingSeries ref = render_pings(r->scene);
    CHECK(r->pings->level_db == ref.level_db); // the worker's pings are the headless ones, byte for byte
    REQUIRE(r->ping_image);
    CHECK(r->ping_image->height == 12);
    CHECK(r->ping_image->width == 2 * r->scene.sonar.range_bins);
    const std::string prefix = test::ui_out_path("session_sidescan");
    REQUIRE(session.snapshot(prefix, {}));
    for (const char* suffix : {".png", ".npy", "_waterfall.npy", ".xtf", ".json"})
        CHECK(std::filesystem::is_regular_file(prefix + suffix));
    // Values that steer the sampler: the waterfall keeps its pings' rays (re-shaded, their estimate made
    // anew meets the tolerances), which a fresh series would place otherwise; a snapshot places them anew,
    // so its files are what `render` writes.
    REQUIRE(session.set("seafloor.material.nu_db", -27.0));
    REQUIRE(session.set("water.depth_m", 3000.0)); // the absorption: the rays would go elsewhere
    REQUIRE(session.wait_full(60s));
    REQUIRE(session.shown()->pings);
    CHECK(session.shown()->pings->rays_traced == 0);
    CHECK(session.shown()->pings->kept_placement_profiles == 24);
    const PingSeries anew = render_pings(session.scene());
    CHECK(session.shown()->pings->level_db != anew.level_db);
    const std::string kept_prefix = test::ui_out_path("session_sidescan_kept");
    REQUIRE(session.snapshot(kept_prefix, {}));
    CHECK(session.shown()->pings->kept_placement_profiles == 0);
    CHECK(decode_npy_values(test::read_bytes(kept_prefix + ".npy"), kept_prefix + ".npy",
                            anew.level_db.size()) == anew.level_db);
    // To a scan: one step per head angle, the image a square sweep.
    REQUIRE(session.set("sonar.kind", "scanning"));
    REQUIRE(session.set("scanning.sector_start_deg", -30.0));
    REQUIRE(session.set("scanning.sector_end_deg", 30.0));
    REQUIRE(session.set("scanning.step_deg", 3.0));
    REQUIRE(session.wait_full(60s));
    r = session.shown();
    REQUIRE(r->pings);
    CHECK(r->pings->pings == 21);
    CHECK(r->pings->channels == 1);
    CHECK(r->ping_image->width == r->ping_image->height);
    // Back to the imaging sonar: a fan again.
    REQUIRE(session.set("sonar.kind", "imaging"));
    REQUIRE(session.wait_full(60s));
    CHECK(session.shown()->frame);
    CHECK_FALSE(session.shown()->pings);
}

TEST_CASE("a side-scan on a played trajectory: the waterfall's pings follow the track and scroll, the new "
          "pings traced and the others kept byte for byte",
          "[ui][session][kinds]") {
    SceneDesc s = default_scene();
    apply_setting(s, "sonar.kind", "sidescan", "test");
    s.sidescan.pings = 10;
    validate_scene(s, "test");
    ui::Session session(s);
    const auto line = std::make_shared<const Trajectory>(
        Trajectory{{0.0, {{-1, 2, 1.5}, {0, 0, 0}}}, {4.0, {{3, 2, 1.5}, {0, 0, 0}}}});
    const double dt = kind_ping_interval_s(s, sound_speed_m_s(s.water.temperature_c, s.water.depth_m));
    session.set_ping_track(line, 1.0);
    REQUIRE(session.wait_full(60s));
    const auto before = session.shown()->pings;
    REQUIRE(before);
    const auto newest = std::int64_t(std::floor(1.0 / dt + 1e-9));
    CHECK(before->schedule.back().number == newest);
    CHECK(before->schedule.back().vehicle.position_m[0] == Approx(-1 + double(newest) * dt).epsilon(1e-9));
    // Two pings later: two new rows at the top (the end of the series), the rest moved down unchanged.
    session.set_ping_track(line, 1.0 + 2 * dt);
    REQUIRE(session.wait_full(60s));
    const auto after = session.shown()->pings;
    REQUIRE(after != before);
    CHECK(after->schedule.back().number == newest + 2);
    const size_t row = size_t(after->channels) * size_t(after->bins);
    CHECK(std::equal(before->level_db.begin() + long(2 * row), before->level_db.end(),
                     after->level_db.begin()));
    CHECK(after->rays_traced > 0);
    CHECK(after->rays_traced < before->rays_traced / 3);
    // Off the track: the scene's own pings again.
    session.set_ping_track(nullptr, 0);
    REQUIRE(session.wait_full(60s));
    CHECK(session.shown()->pings->schedule.back().number == 9);
}

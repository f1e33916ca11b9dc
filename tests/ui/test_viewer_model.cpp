// GL-free parts of the viewer: frame pacing and snapshot requests, undo stack, script parsing, trajectories,
// text layout checks, measurements, the Open dialog's scene filter, the bindings table, the no-echo colour
// and how scenes and objects are named.
#include "support.hpp"

#include "ui/model/bindings.hpp"
#include "ui/model/echo_path_view.hpp"
#include "ui/model/frame_pacer.hpp"
#include "ui/model/image_views.hpp"
#include "ui/model/input_events.hpp"
#include "ui/model/measure.hpp"
#include "ui/model/scene_files.hpp"
#include "ui/model/scene_labels.hpp"
#include "ui/model/script.hpp"
#include "ui/model/script_player.hpp"
#include "ui/model/snapshot.hpp"
#include "ui/model/text_layout.hpp"
#include "ui/model/trajectory.hpp"
#include "ui/model/undo.hpp"

#include "core/base/errors.hpp"
#include "core/display/image.hpp"
#include "core/scene/scene_io.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <set>

using namespace sonarsim;
using namespace sonarsim::ui;

TEST_CASE("undo and redo walk the recorded scenes and a new edit drops the redo states", "[ui][undo]") {
    SceneDesc a = default_scene(), b = a, c = a;
    b.sonar.pose.position_m[0] += 0.5;
    c.objects[0].scale = {2, 2, 2};
    UndoStack u(a);
    CHECK_FALSE(u.record(a)); // unchanged: no step
    CHECK(u.record(b));
    CHECK(u.record(c));
    CHECK(u.undo_steps() == 2);
    auto s = u.undo();
    REQUIRE(s);
    CHECK(same_scene(*s, b));
    s = u.undo();
    REQUIRE(s);
    CHECK(same_scene(*s, a));
    CHECK_FALSE(u.undo());
    s = u.redo();
    REQUIRE(s);
    CHECK(same_scene(*s, b));
    SceneDesc d = a;
    d.sonar.beams = 64;
    CHECK(u.record(d));
    CHECK(u.redo_steps() == 0);
    CHECK_FALSE(u.redo());
    CHECK(same_scene(*u.undo(), b));
}

TEST_CASE("a script plays frame by frame: input before a frame, actions after it, each once",
          "[ui][script]") {
    ScriptPlayer p(
        parse_script("0 move 10 20\n2 move_to sonar.beams 0.5 0.25\n2 press left\n2 screenshot a.png\n"
                     "4 state b.json\n4 release left\n",
                     "s.txt"),
        "s.txt");
    CHECK(p.last_frame() == 5); // the script's last frame + 1
    const std::map<std::string, Rect> widgets = {{"sonar.beams", {100, 200, 40, 8}}};
    auto ev = p.input(0, widgets);
    REQUIRE(ev.size() == 1);
    CHECK(ev[0].pos == glm::dvec2(10, 20));
    CHECK(p.actions(0).empty());
    CHECK(p.input(1, widgets).empty()); // frame 0's steps were taken after it
    CHECK(p.actions(1).empty());
    ev = p.input(2, widgets); // move_to the widget's point, then the press there
    REQUIRE(ev.size() == 2);
    CHECK(ev[0].pos == glm::dvec2(120, 202));
    CHECK(ev[1].type == InputEvent::Type::Press);
    CHECK(ev[1].pos == glm::dvec2(120, 202));
    auto acts = p.actions(2);
    REQUIRE(acts.size() == 1);
    CHECK(acts[0].command == "screenshot");
    CHECK(p.actions(3).empty());
    ev = p.input(4, widgets);
    REQUIRE(ev.size() == 1);
    CHECK(ev[0].type == InputEvent::Type::Release);
    acts = p.actions(4);
    REQUIRE(acts.size() == 1);
    CHECK(acts[0].args[0] == "b.json");
    // A move_to a parameter with no widget names the script's line.
    ScriptPlayer bad(parse_script("0 move_to sonar.nothing 0.5 0.5\n", "bad.txt"), "bad.txt");
    CHECK_THROWS_WITH(bad.input(0, widgets), Catch::Contains("bad.txt") && Catch::Contains("line 1"));
    // The older --drag: hover, press, move linearly, release at the end of `frames`.
    ScriptPlayer drag({}, "", std::nullopt, std::array<glm::dvec2, 2>{glm::dvec2(0, 0), glm::dvec2(10, 0)},
                      5);
    CHECK(drag.last_frame() == 4);
    CHECK(drag.input(0, {}).size() == 1);
    ev = drag.input(1, {});
    REQUIRE(ev.size() == 2);
    CHECK(ev[1].type == InputEvent::Type::Press);
    CHECK(drag.input(2, {})[0].pos == glm::dvec2(5, 0));
    ev = drag.input(4, {});
    REQUIRE(ev.size() == 2);
    CHECK(ev[1].type == InputEvent::Type::Release);
    CHECK(ev[1].pos == glm::dvec2(10, 0));
}

TEST_CASE("scripts parse into timed steps and keys into the events GLFW sends", "[ui][script]") {
    const auto steps =
        parse_script("# comment\n0 move 10 20\n2 press left\n2 release left\n3 key ctrl+shift+z\n"
                     "3 screenshot out.png\n",
                     "s.txt");
    REQUIRE(steps.size() == 5);
    CHECK(steps[1].frame == 2);
    glm::dvec2 pos{0};
    int held = 0;
    auto ev = step_events(steps[0], pos, held);
    REQUIRE(ev.size() == 1);
    CHECK(pos == glm::dvec2(10, 20));
    ev = step_events(steps[3], pos, held);
    // Ctrl down, Shift down, Z down, Z up, Ctrl up, Shift up.
    REQUIRE(ev.size() == 6);
    CHECK(ev[2].key == key::Z);
    CHECK(ev[2].key_down);
    CHECK(ev[2].mods == (mods::Control | mods::Shift));
    CHECK_FALSE(ev[3].key_down);
    CHECK(held == 0);
    CHECK_FALSE(is_input_command("screenshot"));
    CHECK_THROWS_AS(parse_script("1 move 10\n", "s.txt"), InputError);
    CHECK_THROWS_AS(parse_script("2 key S\n1 key S\n", "s.txt"), InputError);
    CHECK_THROWS_AS(parse_script("0 key shift+q+z\n", "s.txt"), InputError);
    CHECK_THROWS_AS(parse_script("0 fly 1 2\n", "s.txt"), InputError);
    CHECK_THROWS_AS(parse_script("0 move_to sonar.beams x 0.5\n", "s.txt"), InputError);
    const auto rel = parse_script("0 move_by 5 -2\n", "s.txt");
    glm::dvec2 at{10, 10};
    step_events(rel[0], at, held);
    CHECK(at == glm::dvec2(15, 8));
}

TEST_CASE("trajectories round-trip through CSV exactly and interpolate between samples", "[ui][trajectory]") {
    ui::Trajectory t;
    Pose p;
    t.add(0, p);
    t.add(0.5, p); // unchanged: skipped while recording
    p.position_m = {1.0 / 3, 2, 0.9};
    p.orientation_deg = {0, 30, 170};
    t.add(1, p);
    p.orientation_deg[2] = -170; // 20 deg further round, across +-180
    t.add(2, p);
    REQUIRE(t.size() == 3);
    const std::string csv = trajectory_csv(t);
    CHECK(csv.rfind("t,x,y,z,roll_deg,pitch_deg,yaw_deg\n", 0) == 0);
    const ui::Trajectory back = ui::parse_trajectory_csv(csv, "t.csv");
    REQUIRE(back.size() == 3);
    CHECK(back.samples()[1].pose.position_m[0] == 1.0 / 3); // bit-exact
    CHECK(back.at(1.5).orientation_deg[2] == Approx(180).margin(1e-9));
    CHECK(back.at(0.5).position_m[0] == Approx((Pose{}.position_m[0] + 1.0 / 3) / 2));
    CHECK(back.at(-1).position_m == Pose{}.position_m);
    CHECK_THROWS_AS(ui::parse_trajectory_csv("t,x,y\n", "t.csv"), InputError);
    CHECK_THROWS_AS(ui::parse_trajectory_csv(
                        std::string(kTrajectoryHeader) + "\n1,0,0,0,0,0,0\n0,0,0,0,0,0,0\n", "t.csv"),
                    InputError);
    CHECK_THROWS_AS(ui::parse_trajectory_csv(std::string(kTrajectoryHeader) + "\n1,0,0,x,0,0,0\n", "t.csv"),
                    InputError);
}

TEST_CASE("text runs group glyphs per line and find overlaps and cut-off text", "[ui][layout]") {
    const Rect clip{0, 0, 100, 100};
    std::vector<Glyph> g;
    for (int i = 0; i < 5; ++i) g.push_back({{10.0f + 7 * i, 10, 7, 13}, clip, 0}); // "hello"
    for (int i = 0; i < 3; ++i) g.push_back({{10.0f + 7 * i, 30, 7, 13}, clip, 0}); // next line
    auto runs = text_runs(g);
    REQUIRE(runs.size() == 2);
    CHECK(runs[0].glyphs == 5);
    CHECK(runs[0].box.w == Approx(35));
    CHECK(overlapping_runs(runs).empty());
    CHECK(layout_problems(runs, 100, 100).empty());
    // Another window's text drawn over the first line, and a glyph cut by its clip rectangle.
    g.push_back({{30, 14, 7, 13}, clip, 1});
    g.push_back({{95, 60, 7, 13}, clip, 0});
    runs = text_runs(g);
    REQUIRE(runs.size() == 4);
    CHECK(overlapping_runs(runs).size() == 1);
    const std::string p = layout_problems(runs, 100, 100);
    CHECK(p.find("overlap") != std::string::npos);
    CHECK(p.find("cut off") != std::string::npos);
    // A tooltip over the text is on top on purpose.
    runs[2].list_name = "##Tooltip_00";
    CHECK(overlapping_runs(runs).empty());
}

TEST_CASE("image measurements: ruler distance and dB statistics of a region", "[ui][measure]") {
    SonarParams s;
    s.beams = 4, s.range_bins = 4, s.range_min_m = 1, s.range_max_m = 5, s.azimuth_fov_deg = 40;
    ImagePlace a, b;
    a.range_m = 2, a.azimuth_deg = 10, b.range_m = 2, b.azimuth_deg = -10;
    CHECK(image_distance_m(a, b) == Approx(2 * 2 * std::sin(10 * M_PI / 180)));
    PolarImage img;
    img.beams = 4, img.bins = 4;
    img.level_db.assign(16, -INFINITY);
    img.level_db[1 * 4 + 1] = 100; // bin 1 (1.5..2.5 m... centre 2.5 m), beam 1 (az +5)
    img.level_db[1 * 4 + 2] = 90;  // beam 2 (az -5)
    a.range_m = 2.2, a.azimuth_deg = 12, b.range_m = 2.8, b.azimuth_deg = -12;
    const RegionStats st = region_stats(img, s, a, b);
    CHECK(st.cells == 2);
    CHECK(st.echo_cells == 2);
    CHECK(st.max_db == 100);
    CHECK(st.min_db == 90);
    CHECK(st.median_db == Approx(95));
    CHECK(st.mean_db == Approx(10 * std::log10((1e10 + 1e9) / 2)));
}

TEST_CASE("the Open dialog lists scene files and not render metadata", "[ui][files]") {
    const std::string scene = test::ui_out_path("filter_scene.json"),
                      meta = test::ui_out_path("filter_meta.json");
    std::ofstream(scene) << scene_to_json(default_scene()).dump();
    std::ofstream(meta) << R"({"rays_traced": 10, "sonar": {}})";
    CHECK(looks_like_scene_file(scene));
    CHECK_FALSE(looks_like_scene_file(meta));
    CHECK_FALSE(looks_like_scene_file(test::ui_out_path("no_such.json")));
}

TEST_CASE("no echo has its own colour in every map and the maps differ", "[ui][colormap]") {
    PolarImage img;
    img.beams = 2, img.bins = 1;
    img.level_db = {-INFINITY, 50}; // 50 dB is below lo: the map's low end
    DisplayParams d;
    std::set<std::array<std::uint8_t, 3>> tops;
    for (Colormap m : {Colormap::Gray, Colormap::Viridis, Colormap::Copper, Colormap::Hot}) {
        d.colormap = m;
        const Image8 out = polar_color_image(img, d);
        const std::array<std::uint8_t, 3> none{out.pixels[0], out.pixels[1], out.pixels[2]},
            low{out.pixels[3], out.pixels[4], out.pixels[5]};
        CHECK(none == no_echo_rgb(m));
        CHECK(none != low);
        tops.insert(colormap_rgb(m, 0.6));
    }
    CHECK(tops.size() == 4);
}

TEST_CASE("the raw image in colour: each cell's gray level, rounded, through the map; far range on top",
          "[ui][colormap]") {
    PolarImage img;
    img.bins = 70, img.beams = 33;
    img.level_db.resize(size_t(img.bins) * size_t(img.beams));
    for (size_t n = 0; n < img.level_db.size(); ++n)
        img.level_db[n] = n % 13 == 0 ? -INFINITY : float(60 + double((n * 7919) % 7000) / 100);
    img.level_db[5] = std::numeric_limits<float>::quiet_NaN();
    DisplayParams d;
    d.lo_db = 75, d.hi_db = 118;
    for (Colormap m : {Colormap::Gray, Colormap::Viridis, Colormap::Copper, Colormap::Hot}) {
        d.colormap = m;
        const Image8 out = polar_color_image(img, d);
        REQUIRE(out.width == 33);
        REQUIRE(out.height == 70);
        long wrong = 0, continuous_differs = 0;
        for (int b = 0; b < img.bins; ++b)
            for (int i = 0; i < img.beams; ++i) {
                const float v = img.at(b, i);
                const double g = gray_level(v, d.lo_db, d.hi_db);
                const auto want = v > -INFINITY ? colormap_rgb(m, std::lround(g) / 255.0) : no_echo_rgb(m);
                const std::uint8_t* p = &out.pixels[(size_t(img.bins - 1 - b) * 33 + size_t(i)) * 3];
                wrong += std::array<std::uint8_t, 3>{p[0], p[1], p[2]} != want;
                if (v > -INFINITY) continuous_differs += colormap_rgb(m, g / 255.0) != want;
            }
        INFO(int(m));
        CHECK(wrong == 0);
        if (m == Colormap::Gray) CHECK(continuous_differs == 0); // rounding first changes no gray pixel
    }
}

TEST_CASE("every binding has an input and an action and docs/viewer.md names each input", "[ui][bindings]") {
    std::ifstream f(std::string(SONARSIM_SOURCE_DIR) + "/docs/viewer.md");
    const std::string readme((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    REQUIRE(!readme.empty());
    for (const Binding& b : bindings()) {
        CHECK(std::string(b.input).size() > 0);
        CHECK(std::string(b.action).size() > 0);
        INFO(b.input);
        CHECK(readme.find(b.input) != std::string::npos);
    }
}

TEST_CASE("key shortcuts dispatch from the bindings table", "[ui][bindings]") {
    using A = KeyAction;
    auto action = [](int k, int m) {
        const Binding* b = key_binding(k, m);
        return b ? b->key_action : A::None;
    };
    // Plain keys run with Shift or Alt held, never with Ctrl.
    CHECK(action(key::S, 0) == A::Snapshot);
    CHECK(action(key::S, mods::Shift) == A::Snapshot);
    CHECK(action(key::S, mods::Alt) == A::Snapshot);
    CHECK(action(key::S, mods::Control) == A::None);
    CHECK(action(key::P, 0) == A::TogglePolar);
    CHECK(action(key::H, 0) == A::ToggleHits);
    CHECK(action(key::B, 0) == A::ToggleMultipath);
    CHECK(action(key::F, 0) == A::ResetCamera);
    CHECK(action(key::O, 0) == A::OpenScene);
    CHECK(action(key::M, 0) == A::StartMeasure);
    CHECK(action(key::R, 0) == A::ToggleRecord);
    CHECK(action(key::Space, 0) == A::TogglePlay);
    CHECK(action(key::Q, 0) == A::None);
    CHECK(action(key::A, 0) == A::None);
    // Ctrl chords.
    CHECK(action(key::Z, mods::Control) == A::Undo);
    CHECK(action(key::Z, mods::Control | mods::Alt) == A::Undo);
    CHECK(action(key::Z, mods::Control | mods::Shift) == A::Redo);
    CHECK(action(key::Y, mods::Control) == A::Redo);
    CHECK(action(key::Y, mods::Control | mods::Shift) == A::Redo);
    CHECK(action(key::Y, 0) == A::None);
    CHECK(action(key::Z, 0) == A::None);
    CHECK(action(key::Q, mods::Control) == A::Quit);
    CHECK(action(key::Q, mods::Control | mods::Shift) == A::Quit);
    // Escape with any modifiers, and also while a text field has the keys; nothing else is.
    for (int m = 0; m < 8; ++m) CHECK(action(key::Escape, m) == A::Cancel);
    for (const Binding& b : bindings()) {
        INFO(b.input);
        CHECK(b.keys.empty() == (b.key_action == A::None)); // keys run an action, an action has keys
        CHECK(b.while_typing == (b.key_action == A::Cancel));
        // No press runs two rows: the first match is the only one.
        for (const KeyMatch& k : b.keys)
            for (int m = 0; m < 8; ++m)
                if (k.matches(k.key, m)) CHECK(key_binding(k.key, m) == &b);
    }
}

TEST_CASE("menu shortcut labels come from the bindings table", "[ui][bindings]") {
    // A key row's input text is its presses, as Help -> Controls shows it.
    for (const Binding& b : bindings())
        if (b.key_action == KeyAction::Redo) CHECK(b.input == "Ctrl+Shift+Z or Ctrl+Y");
    CHECK(shortcut_text(KeyAction::OpenScene) == "O");
    CHECK(shortcut_text(KeyAction::Snapshot) == "S");
    CHECK(shortcut_text(KeyAction::Quit) == "Ctrl+Q");
    CHECK(shortcut_text(KeyAction::Undo) == "Ctrl+Z");
    CHECK(shortcut_text(KeyAction::Redo) == "Ctrl+Shift+Z");
    CHECK(shortcut_text(KeyAction::StartMeasure) == "M");
    CHECK(shortcut_text(KeyAction::TogglePlay) == "Space");
    CHECK(shortcut_text(KeyAction::Cancel) == "Escape");
    CHECK(shortcut_text(KeyAction::None).empty());
    // Every key row's input names its first key press.
    for (const Binding& b : bindings())
        if (!b.keys.empty()) CHECK(b.input.find(key_text(b.keys.front())) != std::string::npos);
}

TEST_CASE("the A-scan keeps its azimuth when the beam count changes", "[ui][ascan]") {
    // +1.2 deg is in beam 59 of 128 over 32 deg (0.25 deg each), beam 29 of 64, beam 118 of 256.
    const double az = 1.2;
    auto grid = [](int beams) {
        SonarParams s;
        s.azimuth_fov_deg = 32, s.beams = beams;
        return SonarGrid(s);
    };
    CHECK(beam_at_azimuth(az, grid(128)) == 59);
    CHECK(beam_at_azimuth(az, grid(64)) == 29);
    CHECK(beam_at_azimuth(az, grid(256)) == 118);
    CHECK(beam_at_azimuth(40, grid(64)) == 0);   // beyond port: the nearest beam
    CHECK(beam_at_azimuth(-40, grid(64)) == 63); // beyond starboard
}

TEST_CASE("the hover readout names a path direct or ghost and its scatterer", "[ui][multipath]") {
    EchoPath p;
    CHECK(echo_path_text(p).empty()); // nothing echoes
    p.points_m = {{0, 0, 1}, {5, 0, 0}, {0, 0, 1}};
    p.object_id = 0;
    CHECK(echo_path_text(p) == "direct echo (seafloor)");
    p.points_m.insert(p.points_m.begin() + 1, {2, 0, 2});
    p.bounces = 1, p.out_bounces = 1, p.object_id = 3;
    CHECK(echo_path_text(p) == "ghost: 1 reflection (scatterer: object 2)");
    p.bounces = 2, p.object_id = -2;
    CHECK(echo_path_text(p) == "ghost: 2 reflections (scatterer: water surface)");
}

TEST_CASE("only the paper's Fig. 9 scene is the Fig. 9 scene", "[ui][labels]") {
    const std::string dir = std::string(SONARSIM_SOURCE_DIR) + "/assets/scenes/";
    CHECK(is_paper_fig9_scene(default_scene()));
    CHECK(is_paper_fig9_scene(load_scene(dir + "fig9.json")));
    CHECK(is_paper_fig9_scene(load_scene(dir + "fig9_pose2.json")));
    for (const char* other : {"monterey.json", "shipwreck.json", "tank.json", "floor.json"}) {
        CAPTURE(other);
        CHECK_FALSE(is_paper_fig9_scene(load_scene(dir + other)));
    }
    SceneDesc bigger = default_scene();
    bigger.objects[0].box_m = Vec3d{0.1, 0.12, 0.22};
    CHECK_FALSE(is_paper_fig9_scene(bigger));
}

TEST_CASE("the object combo names objects by the scene's name, else by their shape", "[ui][labels]") {
    const std::string dir = std::string(SONARSIM_SOURCE_DIR) + "/assets/scenes/";
    const SceneDesc wreck = load_scene(dir + "shipwreck.json");
    CHECK(object_label(wreck, 0).rfind("object 0: sunken ship (DAVE", 0) == 0);
    CHECK(object_label(wreck, 0).find(".ply") == std::string::npos);
    CHECK(object_tooltip(wreck, 0).find("../meshes/shipwreck_sunken_ship_dave.ply") != std::string::npos);
    CHECK(object_label(default_scene(), 0) == "object 0: box 0.07 x 0.12 x 0.22 m");
    SceneDesc unnamed = wreck;
    unnamed.objects[0].name.clear();
    CHECK(object_label(unnamed, 0) == "object 0: shipwreck_sunken_ship_dave.ply");
}

TEST_CASE("the frame pacer sleeps when idle, owes settle frames after it, and counts each image once",
          "[ui][pacer]") {
    FramePacer p;
    CHECK_FALSE(p.poll_now(false)); // idle: wait for input
    CHECK(p.owed_frames() == FramePacer::kSettleFrames);
    for (int i = 0; i < FramePacer::kSettleFrames; ++i) CHECK(p.poll_now(false));
    CHECK_FALSE(p.poll_now(false)); // settled: wait again
    CHECK(p.poll_now(true));        // a script, --orbit, a playing trajectory: never waits
    CHECK(p.owed_frames() == 1);
    p.keep_drawing();
    CHECK(p.owed_frames() == FramePacer::kSettleFrames);

    p.begin_frame();
    p.end_frame();
    CHECK(p.last_frame_ms() >= 0);
    CHECK(p.stats().frame_ms.size() == 1);

    RenderResult r;
    r.wall_ms = 12.5;
    p.count_image(1, r, false); // frame 0 of --orbit: counted, not recorded
    p.count_image(1, r, true);  // the same image on the next frame: not again
    CHECK(p.stats().image_ms.empty());
    r.wall_ms = 7;
    p.count_image(2, r, true);
    p.count_image(2, r, true);
    REQUIRE(p.stats().image_ms.size() == 1);
    CHECK(p.stats().image_ms[0] == 7);
    CHECK(p.stats().estimate_median_db.empty()); // no frame, no estimate

    // An image with an estimate: its median and the screen's precision of its display range.
    auto f = std::make_shared<Frame>();
    f->error_estimate.valid = true;
    f->error_estimate.median_abs_db = 0.07;
    f->display.lo_db = 50, f->display.hi_db = 101;
    r.frame = f;
    p.count_image(3, r, true);
    REQUIRE(p.stats().estimate_median_db.size() == 1);
    CHECK(p.stats().estimate_median_db[0] == 0.07);
    CHECK(p.stats().screen_median_db[0] == Approx(0.1)); // half of 51 dB / 255 grey levels
}

TEST_CASE("snapshot requests wait for the full-quality image and take each one once", "[ui][snapshot]") {
    SnapshotRequests q;
    int taken = 0;
    CHECK(q.serve(false, [&] { ++taken; })); // nothing asked: nothing to wait for
    q.ask();
    q.ask();
    CHECK_FALSE(q.serve(false, [&] { ++taken; })); // a preview on screen: none taken
    CHECK(taken == 0);
    CHECK(q.pending() == 2);
    CHECK(q.serve(true, [&] { ++taken; }));
    CHECK(taken == 2);
    CHECK(q.pending() == 0);
    q.written();
    CHECK(q.written_count() == 1);
}

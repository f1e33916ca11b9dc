// Snapshot round trip: the scene file a snapshot writes reproduces its raw image exactly through
// load_scene + render (what `sonarsim render --scene` does), even after incremental edits in the viewer.
#include "support.hpp"

#include "ui/model/render_worker.hpp"
#include "ui/model/snapshot.hpp"

#include "core/io/output.hpp"
#include "core/scene/scene_io.hpp"
#include "core/pipeline/simulator.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <chrono>
#include <filesystem>

using namespace sonarsim;

TEST_CASE("snapshot files -> load_scene -> render gives identical .npy and PNG bytes", "[ui][snapshot]") {
    for (const char* scheme : {"adaptive", "spread", "uniform"}) {
        INFO("sampling.scheme = " << scheme);
        // A viewer session through the viewer's worker: the first image, then a drag (retrace), a physics
        // change (re-shade) and a display change (re-map), each applied incrementally by one Simulator.
        SceneDesc s = default_scene();
        apply_setting(s, "sampling.scheme", scheme, "test");
        ui::RenderWorker worker;
        auto run = [&](bool keep_placement = true) {
            const auto id = worker.request(s, false, false, std::nullopt, 0, {}, keep_placement);
            REQUIRE(worker.wait_for(id, std::chrono::seconds(60)));
            auto r = worker.take();
            REQUIRE(r);
            REQUIRE(r->frame);
            return *r;
        };
        run();
        s.sonar.pose.position_m = {0.41, 2.37, 0.93};
        s.sonar.pose.orientation_deg = {1.3, 27.4, -36.125};
        run();
        s.sonar.source_level_db = 221.7;
        s.water.temperature_c = 13.3;
        s.objects[0].material.nu_db = -31.4;
        run();
        s.display.lo_db = 71.1;
        s.display.colormap = Colormap::Viridis;
        ui::RenderResult shown = run();
        CHECK(shown.stage == Stage::Display);
        // The temperature and nu steer the adaptive sampler: the viewer kept its rays, re-shaded (their
        // estimate made anew meets the tolerances). A snapshot places them anew first, as Session::snapshot
        // does, so that its files are what `render` makes of its scene.
        CHECK(shown.frame->placement_kept == (std::string(scheme) == "adaptive"));
        if (shown.frame->placement_kept) {
            const auto kept_hits = shown.frame->hits_ptr;
            shown = run(false);
            CHECK_FALSE(shown.frame->placement_kept);
            CHECK(shown.frame->hits_ptr != kept_hits);
        }

        const std::string prefix = test::ui_out_path(std::string("snapshot_roundtrip_") + scheme);
        const Bytes fake3d = {1, 2, 3};
        const Bytes fake_annotated = {4, 5, 6};
        const auto paths =
            ui::write_snapshot(prefix, shown.scene, *shown.frame, fake3d, nullptr, fake_annotated);
        REQUIRE(paths.size() == 7); // every file written is listed, the annotated panel included
        for (auto& p : paths) CHECK(std::filesystem::exists(p));
        CHECK(std::count(paths.begin(), paths.end(), prefix + "_annotated.png") == 1);
        const bool same_3d = test::read_bytes(prefix + "_3d.png") == fake3d;
        CHECK(same_3d);
        CHECK(test::read_bytes(prefix + "_annotated.png") == fake_annotated);

        // What `sonarsim render --scene PREFIX_scene.json` does.
        const SceneDesc again = load_scene(prefix + "_scene.json");
        CHECK(changed_stage(again, shown.scene) == Stage::None);
        Simulator fresh(again);
        const auto g = fresh.render();
        const bool same_npy = test::read_bytes(prefix + ".npy") == encode_npy(g->polar());
        const bool same_png = test::read_bytes(prefix + ".png") == encode_png(g->sector());
        CHECK(same_npy);
        CHECK(same_png);
    }
}

TEST_CASE("default snapshot prefixes do not overwrite earlier snapshots", "[ui][snapshot]") {
    const std::string dir = test::ui_out_path("prefix_dir");
    std::filesystem::create_directories(dir);
    const std::string a = ui::default_snapshot_prefix(dir);
    write_files_atomically({{a + ".npy", Bytes{0}}});
    const std::string b = ui::default_snapshot_prefix(dir);
    CHECK(a != b);
    CHECK(a.rfind(dir, 0) == 0);
    std::filesystem::remove(a + ".npy");
}

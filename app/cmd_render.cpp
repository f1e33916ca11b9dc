// `sonarsim render`: one image of a scene, written as PNG, .npy and metadata JSON.
#include "commands.hpp"
#include "load.hpp"
#include "status_line.hpp"

#include "core/io/ground_truth_files.hpp"
#include "core/base/errors.hpp"
#include "core/shading/ground_truth.hpp"
#include "core/io/output.hpp"
#include "core/io/ping_output.hpp"
#include "core/kinds/ping_series.hpp"
#include "core/pipeline/memory_report.hpp"
#include "core/pipeline/simulator.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

#ifdef SONARSIM_HAVE_VIEWER
#include "ui/gl/view3d.hpp"
#endif

namespace sonarsim::app {
namespace {

struct RenderOptions {
    SceneOptions scene;
    std::string out;
    std::string view3d; ///< PNG of the 3D view (headless EGL)
    bool ground_truth = false;
    bool ground_truth_maps = false; ///< also the 16-bit PNG maps (implies ground_truth)
    std::string trajectory;         ///< a side-scan's or scan's pings along it
    double at_s = 0;                ///< the newest ping's time on it (when at_given)
    bool at_given = false;          ///< --at was on the command line
};

/// The 3D view as PNG bytes, drawn without any display (EGL, Mesa surfaceless).
std::vector<std::uint8_t> view3d_png(const SceneDesc& scene) {
#ifdef SONARSIM_HAVE_VIEWER
    return ui::view3d_png_headless(scene, 1024, 768);
#else
    (void)scene;
    throw InputError("--view3d", "", "this build has no viewer (SONARSIM_BUILD_VIEWER=OFF)");
#endif
}

/// "trace 120 ms (shading included), image 30 ms": each stage that ran, the adaptive tracer's shading in
/// its trace time.
std::string stage_times(const Frame& f) {
    auto ms = [](double t) { return std::to_string(int(std::lround(t))) + " ms"; };
    std::string text = "trace " + ms(f.trace_ms);
    text += f.shade_ms > 0 ? ", shade " + ms(f.shade_ms) : " (shading included)";
    if (f.sensor_applied()) text += ", sensor " + ms(f.sensor_ms);
    return text + ", image " + ms(f.image_ms);
}

/// "; estimated error 0.94 % rel L1, 0.002 dB median: tolerances met" (the sampler's own estimate), or
/// nothing for a sampling that makes none.
std::string estimate_text(const Frame& f, const SceneDesc& s) {
    const auto& e = f.error_estimate;
    if (!e.valid) return "";
    char buf[160];
    std::snprintf(buf, sizeof buf, "; estimated error %.3g %% rel L1, %.2g dB median: tolerances %s",
                  100 * e.rel_l1, e.median_abs_db, e.meets(s.sampling) ? "met" : "not met");
    return buf;
}

void check_parent_dir(const std::string& path, const std::string& option) {
    const std::filesystem::path p(path);
    if (p.filename().empty() || p.filename() == "." || p.filename() == "..")
        throw InputError(option, "",
                         "\"" + path + "\" names a directory; give a file name prefix, e.g. dir/image");
    const auto dir = p.parent_path().empty() ? std::filesystem::path(".") : p.parent_path();
    std::error_code ec;
    if (!std::filesystem::is_directory(dir, ec)) {
        // A file where a directory of the path should be is in the way; otherwise the directory is missing.
        for (auto up = dir; !up.empty(); up = up.parent_path()) {
            if (std::filesystem::exists(up, ec) && !std::filesystem::is_directory(up, ec))
                throw InputError(option, "",
                                 "\"" + up.string() +
                                     "\" is a file, not a directory: it is in the way of \"" + path + "\"");
            if (up == up.parent_path()) break;
        }
        throw InputError(option, "", "directory \"" + dir.string() + "\" does not exist");
    }
}

/// A side-scan's waterfall or a scanning sonar's sweep: its pings traced one by one, progress on a terminal.
int run_render_pings(const RenderOptions& o, const SceneDesc& scene) {
    StatusLine status;
    PingControl control;
    control.ground_truth = o.ground_truth;
    if (!o.trajectory.empty())
        control.schedule = ping_schedule_along_file(scene, o.trajectory,
                                                    o.at_given ? std::optional<double>(o.at_s) : std::nullopt,
                                                    "--trajectory", "--at");
    control.progress = [&](int done, int all) {
        if (done % 16 == 0 || done == all)
            status.show("ping " + std::to_string(done) + " of " + std::to_string(all));
    };
    const PingSeries series = render_pings(scene, control);
    status.clear();
    write_ping_files(o.out, scene, series);
    char timing[160];
    std::snprintf(timing, sizeof timing, "%d pings x %d channel(s) x %d bins in %.0f ms (%.2f ms a ping), ",
                  series.pings, series.channels, series.bins, series.trace_ms,
                  series.trace_ms / series.pings);
    std::cout << "wrote " << ping_outputs_text(o.out, scene) << "\n"
              << timing << "rays " << series.rays_traced << ", ping interval " << series.ping_interval_s * 1e3
              << " ms (" << series.pings * series.ping_interval_s << " s of sonar time)\n";
    if (o.ground_truth)
        std::cout << "wrote " << o.out << "_gt_*.npy (ground truth per sample, shaped as " << o.out
                  << ".npy)\n";
    return 0;
}

int run_render(const RenderOptions& o) {
    const SceneDesc scene = load_scene_from_options(o.scene);
    if (!o.trajectory.empty() && scene.sonar.kind == SonarKind::Imaging)
        throw InputError(
            "--trajectory", "",
            "render takes a trajectory for a side-scan's or scan's pings (sonar.kind sidescan or "
            "scanning); an imaging sonar's frames along one: sonarsim batch --trajectory");
    if (!o.trajectory.empty() && !o.view3d.empty())
        throw InputError("--trajectory", "", "draws no 3D view; leave out --view3d");
    if (o.at_given && o.trajectory.empty())
        throw InputError("--at", "", "is a time on a trajectory: give --trajectory FILE too");
    if (o.ground_truth_maps && scene.sonar.kind != SonarKind::Imaging)
        throw InputError("--ground-truth-png", "",
                         "maps an imaging sonar's range bins and beams; a side-scan's or scan's ground truth "
                         "per sample: --ground-truth");
    if (scene.sonar.kind != SonarKind::Imaging && !o.out.empty() && o.view3d.empty()) {
        check_parent_dir(o.out, "--out");
        return run_render_pings(o, scene);
    }
    if (!o.out.empty()) check_parent_dir(o.out, "--out");
    if (!o.view3d.empty()) check_parent_dir(o.view3d, "--view3d");
    std::vector<std::pair<std::string, std::vector<std::uint8_t>>> extra;
    if (!o.view3d.empty()) extra.emplace_back(o.view3d, view3d_png(scene));
    if (o.out.empty()) {
        write_files_atomically(extra);
        std::cout << "wrote " << o.view3d << " (3D view)\n";
        return 0;
    }

    Simulator sim(scene);
    sim.request({o.ground_truth, false});
    const auto f = sim.render();
    json more;
    if (o.ground_truth) {
        GroundTruthOutputs gt = ground_truth_outputs(o.out, *f->truth_ptr, scene, true, o.ground_truth_maps);
        for (auto& file : gt.files) extra.push_back(std::move(file));
        more = std::move(gt.metadata);
    }
    write_render_files(o.out, scene, *f, std::move(extra), more);
    if (o.ground_truth) std::cout << "wrote " << o.out << "_gt_*.npy (ground truth per range bin and beam)\n";
    if (o.ground_truth_maps)
        std::cout << "wrote " << o.out << "_gt_range_m.png, " << o.out
                  << "_gt_elevation_deg.png (16-bit maps; their scale in " << o.out << ".json)\n";
    if (!o.view3d.empty()) std::cout << "wrote " << o.view3d << " (3D view)\n";
    std::cout << "wrote " << render_outputs_text(o.out, &scene) << "; image " << f->polar().bins << " x "
              << f->polar().beams << ", sector " << f->sector().width << "x" << f->sector().height << "\n"
              << "rays " << f->hits().rays_traced << ", " << stage_times(*f) << estimate_text(*f, scene)
              << "\n"
              << "memory kept: " << to_string(memory_report()) << "\n";
    return 0;
}

} // namespace

void register_render(CLI::App& app, std::function<int()>& run) {
    auto o = std::make_shared<RenderOptions>();
    CLI::App* cmd = app.add_subcommand("render", "Render one sonar image headless (PNG, .npy, .json)");
    add_scene_options(*cmd, o->scene);
    cmd->add_option("--out", o->out, "Output prefix: writes " + render_outputs_text("PREFIX"));
    cmd->add_flag("--ground-truth", o->ground_truth,
                  "Also write PREFIX_gt_<name>.npy: per range bin and beam the elevation (mean, min, max), "
                  "point, object id, incidence, number of surfaces behind it and reflections (multipath); a "
                  "side-scan or scan: per ping, channel and sample");
    cmd->add_flag("--ground-truth-png", o->ground_truth_maps,
                  "Also write the ground truth as 16-bit gray PNG maps laid out as PREFIX_polar.png: "
                  "PREFIX_gt_range_m.png (distance to what echoes) and PREFIX_gt_elevation_deg.png, their "
                  "scale in PREFIX.json and in each PNG's text (implies --ground-truth)");
    cmd->add_option(
        "--trajectory", o->trajectory,
        "A side-scan or scan: its pings heard along this trajectory CSV (batch's format): ping k at "
        "k x the ping interval after its start, from its pose then; the newest at --at");
    cmd->add_option("--at", o->at_s,
                    "With --trajectory: the newest ping's time on it [s] (default: its end)");
    cmd->add_option(
        "--view3d", o->view3d,
        "Also draw the 3D view (scene, sonar, field of view) into this PNG, with no display (EGL)");
    cmd->callback([o, cmd, &run] {
        o->at_given = cmd->count("--at") > 0;
        o->ground_truth = o->ground_truth || o->ground_truth_maps;
        if (o->out.empty() && o->view3d.empty()) throw CLI::RequiredError("--out");
        run = [o] { return run_render(*o); };
    });
}

} // namespace sonarsim::app

// `sonarsim batch`: one frame per pose of a trajectory (a CSV file, a circle or a line) into a dataset
// directory, optionally one shard of it, resumable; then, on request, the ARIS and MCAP files of the dataset.
// A side-scan's or scanning sonar's frame is its waterfall or sweep from the frame's pose.
#include "commands.hpp"
#include "load.hpp"
#include "status_line.hpp"

#include "core/base/errors.hpp"
#include "core/dataset/batch.hpp"
#include "core/dataset/export.hpp"
#include "core/dataset/containers.hpp"
#include "core/kinds/pings.hpp"
#include "core/scene/params.hpp"

#include <atomic>
#include <csignal>
#include <ctime>
#include <cstdio>
#include <iostream>
#include <memory>

namespace sonarsim::app {
namespace {

struct BatchCliOptions {
    SceneOptions scene;
    std::string trajectory, circle, line, out, shard, aris, mcap;
    std::string mcap_dtype = "uint8";
    double rate_hz = 10.0;
    bool resume = false;
    bool ground_truth = false;
    bool ground_truth_maps = false;
    bool start_now = false;
};

std::string progress_text(const BatchProgress& p) {
    const int width = 30;
    const int filled = int(double(width) * double(p.done) / double(std::max<size_t>(p.total, 1)));
    const double rate = p.elapsed_s > 0 ? double(p.rendered) / p.elapsed_s : 0;
    const double eta = rate > 0 ? double(p.total - p.done) / rate : 0;
    char b[160];
    std::snprintf(b, sizeof b, "[%s%s] %zu/%zu frames  %.2f frames/s  ETA %d:%02d",
                  std::string(size_t(filled), '#').c_str(), std::string(size_t(width - filled), '-').c_str(),
                  p.done, p.total, rate, int(eta) / 60, int(eta) % 60);
    return b;
}

/// Set by the first SIGINT (Ctrl-C) or SIGTERM (a Slurm time limit): the run ends after the frame in flight,
/// with its index. A second signal ends the process at once.
std::atomic<bool> g_stop{false};
std::atomic<int> g_signal{0};
static_assert(std::atomic<bool>::is_always_lock_free && std::atomic<int>::is_always_lock_free);

extern "C" void on_stop_signal(int sig) {
    g_signal.store(sig);
    g_stop.store(true);
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
}

int run_batch_command(const BatchCliOptions& o) {
    SceneDesc scene = load_scene_from_options(o.scene);
    if (o.start_now) { // the wall clock, asked for; without it the dataset's start is a fixed time
        if (scene.exports.start_time_s > 0)
            throw InputError("--start-now", "",
                             "export.start_time_s is given too: give either the start or --start-now");
        scene.exports.start_time_s = double(std::time(nullptr));
    }
    const Trajectory trajectory =
        make_trajectory(o.trajectory, o.circle, o.line, o.rate_hz, scene.sonar.pose.orientation_deg);
    BatchOptions options;
    if (!o.shard.empty()) options.frames = shard_frames(o.shard, trajectory.size(), "--shard");
    options.resume = o.resume;
    options.ground_truth =
        o.ground_truth || o.ground_truth_maps; // the maps come with the arrays, as in render
    options.ground_truth_maps = o.ground_truth_maps;
    if (o.ground_truth_maps && scene.sonar.kind != SonarKind::Imaging)
        throw InputError("--ground-truth-png", "",
                         "maps an imaging sonar's range bins and beams; a side-scan's or scan's ground truth "
                         "per sample: --ground-truth");
    StatusLine status;
    options.progress = [&](const BatchProgress& p) { status.show(progress_text(p)); };
    // The containers asked for (a row of dataset_containers each), checked before anything is rendered.
    std::vector<std::pair<const DatasetContainer*, std::string>> packs;
    if (!o.aris.empty()) packs.emplace_back(&dataset_container("--aris"), o.aris);
    if (!o.mcap.empty()) packs.emplace_back(&dataset_container("--mcap"), o.mcap);
    for (const auto& [container, path] : packs) check_holds(*container, scene, container->option);
    if (scene.sonar.kind != SonarKind::Imaging) { // each frame a waterfall or sweep: the timing said once
        std::string line = ping_timing_text(scene);
        if (trajectory.size() > 1) {
            char b[160];
            std::snprintf(b, sizeof b, "; the trajectory's frames are %.3f s apart",
                          (trajectory.back().t_s - trajectory.front().t_s) / double(trajectory.size() - 1));
            line += b;
        }
        line += scene.sonar.motion_from_trajectory
                    ? "; each frame's pings move along the trajectory (sonar.motion_from_trajectory)"
                    : "; each frame's pings are heard from the frame's pose (sonar.motion_from_trajectory "
                      "true moves them along the trajectory)";
        std::cout << line << "\n";
    }
    for (const auto& [container, path] : packs) { // before rendering: the scene as the file records it
        const std::string origin = o.scene.scene_file.empty() ? container->option : o.scene.scene_file;
        if (container->prepare) {
            std::string note;
            const SceneDesc prepared = container->prepare(scene, origin, note);
            // A dataset begun without it keeps its grid (resumed, its frames must agree): the file resamples.
            if (!note.empty() && dataset_holds_other_scene(o.out, prepared) &&
                !dataset_holds_other_scene(o.out, scene))
                note = "the dataset in " + o.out + " was begun on its own range grid, which it keeps: its " +
                       "frames are resampled onto the samples of the " + container->name +
                       " (a new dataset with " + container->option + " renders on them)";
            else
                scene = prepared;
            if (!note.empty()) std::cout << path << ": " << note << "\n";
        }
        if (container->check_times)
            container->check_times(scene, trajectory, origin, o.trajectory.empty() ? "--rate" : o.trajectory);
    }
    prepare_dataset(o.out, scene, trajectory);
    options.stop = &g_stop;
    std::signal(SIGINT, on_stop_signal);
    std::signal(SIGTERM, on_stop_signal);
    const BatchSummary r = run_batch(o.out, options);
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
    status.clear();
    std::printf(
        "rendered %zu frames (%zu already complete) in %.1f s (%.2f frames/s) into %s; index.csv lists "
        "%zu of %zu frames\n",
        r.rendered, r.skipped, r.elapsed_s, r.elapsed_s > 0 ? double(r.rendered) / r.elapsed_s : 0.0,
        o.out.c_str(), r.indexed, trajectory.size());
    if (r.interrupted) {
        std::fflush(stdout);
        std::fprintf(stderr,
                     "sonarsim: interrupted (%s) after the frame in flight; the same command with --resume "
                     "renders the %zu frames not yet complete%s\n",
                     g_signal.load() == SIGTERM ? "SIGTERM" : "Ctrl-C", trajectory.size() - r.indexed,
                     o.aris.empty() && o.mcap.empty() ? "" : " and then writes --aris/--mcap");
        return 128 + g_signal.load();
    }
    // The export keys of this command line (they are no part of the dataset): one mapping per file.
    const bool imaging = scene.sonar.kind == SonarKind::Imaging;
    const size_t items = imaging ? trajectory.size() : ping_schedule(scene).size() * trajectory.size();
    for (const auto& [container, path] : packs) {
        const bool float32 = container->holds_float32 && o.mcap_dtype == "float32";
        const ExportReport x =
            export_dataset(o.out, path, *container, float32, scene.exports, container->option);
        std::string line = "wrote " + path + " (" + container->name + ", " + std::to_string(items) + " " +
                           (imaging ? container->frame_items : container->ping_items);
        line += float32 ? ")" : "; " + x.summary() + ") and " + path + ".json";
        std::cout << line << "\n";
        if (const std::string w = float32 ? "" : x.warning(path); !w.empty())
            std::cerr << "sonarsim: " << w << "\n";
        for (const std::string& note : x.notes) std::cout << path << ": " << note << "\n";
    }
    return 0;
}

} // namespace

void register_batch(CLI::App& app, std::function<int()>& run) {
    auto o = std::make_shared<BatchCliOptions>();
    CLI::App* cmd = app.add_subcommand(
        "batch",
        "Render one frame per pose of a trajectory into a dataset: DIR/frames/NNNNNN.*, DIR/index.csv");
    add_scene_options(*cmd, o->scene);
    cmd->add_option(
        "--trajectory", o->trajectory,
        "CSV file with the header t,x,y,z,roll_deg,pitch_deg,yaw_deg (s, m, deg), one frame per row");
    cmd->add_option("--circle", o->circle,
                    "cx,cy,cz,radius_m,height_m,frames: around the vertical through (cx,cy) at cz+height_m, "
                    "looking at (cx,cy,cz)");
    cmd->add_option("--line", o->line,
                    "x0,y0,z0,x1,y1,z1,frames: from one point to the other, ends included, with the scene's "
                    "orientation");
    cmd->add_option("--rate", o->rate_hz, "Frames per second of --circle and --line (sets t)")
        ->capture_default_str();
    cmd->add_option("--out", o->out, "Dataset directory (created)")->required();
    cmd->add_option("--shard", o->shard,
                    "i/n: render only frames i, i+n, i+2n, ... (e.g. a Slurm array task)");
    cmd->add_flag("--resume", o->resume, "Skip frames that are already complete");
    cmd->add_flag(
        "--start-now", o->start_now,
        "Start the dataset's clock (ARIS FrameTime, MCAP stamps) at the wall clock when it is first "
        "prepared, instead of export.start_time_s (default 2026-01-01 00:00:00 UTC)");
    cmd->add_flag(
        "--ground-truth", o->ground_truth,
        "Also write each frame's NNNNNN_gt_<name>.npy (elevation, point, object id, incidence, "
        "surfaces and reflections per range bin and beam; a side-scan or scan: per ping, channel and "
        "sample)");
    cmd->add_flag("--ground-truth-png", o->ground_truth_maps,
                  "Also write each frame's ground truth as 16-bit gray PNG maps laid out as its _polar.png: "
                  "NNNNNN_gt_range_m.png and NNNNNN_gt_elevation_deg.png, their scale in NNNNNN.json and in "
                  "each PNG's text (implies --ground-truth)");
    cmd->add_option(
        "--aris", o->aris,
        "Also write the dataset as an ARIS recording (.aris; 48, 64, 96 or 128 beams); needs every frame");
    cmd->add_option(
        "--mcap", o->mcap,
        "Also write the dataset as a ROS 2 bag (MCAP) of marine_acoustic_msgs/ProjectedSonarImage (a "
        "side-scan or scan: RawSonarImage, one per ping)");
    cmd->add_option("--mcap-dtype", o->mcap_dtype,
                    "Data of the MCAP messages: uint8 (as ARIS) or float32 (L_EN dB)")
        ->capture_default_str()
        ->check(CLI::IsMember({"uint8", "float32"}));
    cmd->callback([o, &run] { run = [o] { return run_batch_command(*o); }; });
}

} // namespace sonarsim::app

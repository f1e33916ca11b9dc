// sonarsim_bench: the benchmark suite (see bench/README.md). Shared declarations of its parts:
// scenes.cpp (the scene table), worker.cpp (one scene measured in its own process), report.cpp (RESULTS.md,
// CSV, JSON), main.cpp (command line and the driver that runs every scene and subprocess).
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace sonarsim {
class Simulator;
struct Frame;
struct ImageError;
struct SceneDesc;
} // namespace sonarsim

namespace sonarsim::bench {

using json = nlohmann::json;

/// The reference of `devices` and `multipath`: spread, this many elevation rays per beam in this many
/// azimuth columns. 729 x 3 was not enough: on the wide sonars over the wreck it was itself ~1 % off (rel L1
/// 1.3-1.7 % against it, 0.65 % against 2187 x 9, the sampler unchanged).
constexpr int kReferenceRays = 2187;
constexpr int kReferenceColumns = 9;
/// The ideal image of `f` against the reference of its scene `at_pose` (the pose f was rendered from):
/// spread, kReferenceRays x kReferenceColumns, the same bounces (devices.cpp).
ImageError error_against_reference(const Frame& f, SceneDesc at_pose);
/// The floor of an image of `rays` rays of scene `s`: as many rays on a plain beam-ordered grid (spread,
/// one column per beam, rays / beams elevation rays), what tracing, shading and imaging them costs without
/// the adaptive sampler's bookkeeping (devices.cpp).
SceneDesc floor_grid(SceneDesc s, std::uint64_t rays);
/// Median over `repeats` warm images of `s` in `sim` (the yaw nudged each time so that every stage reruns:
/// trace, shade, sensor, display); `last` (if given) keeps the last frame (devices.cpp).
double warm_ms(Simulator& sim, SceneDesc s, int repeats, std::shared_ptr<const Frame>* last);
/// Median trace + shade time of floor_grid(s, rays) over `repeats` warm images (devices.cpp).
double floor_ms(const SceneDesc& s, std::uint64_t rays, int repeats);
/// The median of v (of an even count, the upper of the middle two; 0 when empty).
double median(std::vector<double> v);

/// Where things are.
struct Paths {
    std::string repo;     ///< source checkout (assets/scenes, bench/results)
    std::string shared;   ///< the shared mesh collection (the bunny); may be absent
    std::string work;     ///< generated terrains, scene files, render outputs, logs
    std::string sonarsim; ///< the sonarsim executable (first-image renders, the viewer)
};

struct BenchScene {
    std::string name;  ///< short id, used in file names and --scenes
    std::string title; ///< what it is, for the report
    std::string file;  ///< scene file (JSON) that both the worker and `sonarsim render` load
    long triangles = 0;
    bool heavy = false; ///< left out of --quick
    bool view = false;  ///< also timed in the viewer (`sonarsim view --orbit` under xvfb-run)
    /// timed in the viewer only (no reference, no settings): an example scene whose image the main tables
    /// do not cover (the multipath tank; `sonarsim_bench multipath` measures it)
    bool view_only = false;
    std::string skip; ///< non-empty: why it is skipped
};

/// The benchmark scenes in report order. For the scenes `wanted` accepts, generates what is missing
/// (procedural terrains, scene files) in paths.work; `log` receives one line per file generated. The others
/// come back with an empty `file`.
std::vector<BenchScene> prepare_scenes(const Paths& paths,
                                       const std::function<bool(const BenchScene&)>& wanted,
                                       const std::function<void(const std::string&)>& log);

/// One scene measured in this process: the reference, then every sampling setting. Writes JSON to
/// `json_out`. Returns the exit status.
struct WorkerOptions {
    std::string name, scene_file, json_out;
    bool quick = false;
};
int run_worker(const WorkerOptions& options);

/// Writes RESULTS.md, results.csv and results.json into `out_dir`; returns the Markdown text.
std::string write_reports(const json& results, const std::string& out_dir);

/// `sonarsim_bench sensor`: the sensor stage alone (median of `repeats`), printed as a table; `only`: just
/// the cases whose name contains it.
int run_sensor_bench(int repeats, const std::string& only = "");

/// `sonarsim_bench multipath`: trace + shade with sampling.bounces 0, 1, 2 on the tank and the wreck.
/// `settings`: "key=value" overrides applied to every case (as `sonarsim render --set`).
int run_multipath_bench(const std::string& repo, int repeats, const std::vector<std::string>& settings);

/// `sonarsim_bench devices`: every device preset at its own window over the terrain and the wreck: warm
/// image, rays, error against a reference, the floor and the device's own frame interval, as a Markdown
/// table (rows printed as they are measured). `settings`: "key=value" overrides applied to every row after
/// its preset. `json_out` (if not empty): the rows as JSON ({"repeats", "settings", "rows"}), for RESULTS.md.
int run_devices_bench(const Paths& paths, int repeats, const std::vector<std::string>& only = {},
                      const std::vector<std::string>& settings = {}, const std::string& json_out = "");
/// The devices table's Markdown: its header, one row (a JSON row of run_devices_bench) and the count of live
/// rows, shared by the terminal and RESULTS.md.
std::string devices_table_header();
std::string devices_table_row(const json& row);
std::string devices_table_summary(const json& rows);

/// `sonarsim_bench warm`: each scene file's warm image (median of `repeats`), rays, the sampler's estimate
/// and the floor, one line each (warm.cpp). `settings` as for devices.
int run_warm_bench(const std::vector<std::string>& scenes, int repeats,
                   const std::vector<std::string>& settings);

/// `sonarsim_bench slider`: each physics slider of the viewer dragged over each scene file: the preview
/// image's median wall time, the rays the previews traced, the full image once it rests (slider.cpp).
int run_slider_bench(const std::vector<std::string>& scenes, int repeats);

/// Peak resident set size of this process so far [MB] (getrusage ru_maxrss).
double self_peak_rss_mb();

/// A one-line status on stderr, overwritten in place, only when stderr is a terminal.
void status_line(const std::string& text);

} // namespace sonarsim::bench

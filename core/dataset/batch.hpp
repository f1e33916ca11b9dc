// Datasets along a trajectory: one frame per pose, written as `render` writes it, with an index.
//
// Layout of DIR: scene.json (the base scene), trajectory.csv (every pose), frames/NNNNNN.* (the files of
// render_outputs() for frame N), index.csv (one row per complete frame). Each frame's files are written in
// one atomic step, so a killed run loses at most the frame in flight; a frame counts as complete when all its
// files exist. index.csv is rebuilt from the complete frames at the end of every run (under a lock, so
// concurrent shards end with a full index).
#pragma once
#include "core/data/polar_image.hpp"
#include "core/data/scene.hpp"
#include "core/data/trajectory.hpp"
#include "core/io/ros2_pings.hpp"

#include <atomic>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace sonarsim {

/// "i/n" with 0 <= i < n: the frames i, i + n, i + 2n, ... of a trajectory of `total` frames.
std::vector<size_t> shard_frames(const std::string& spec, size_t total, const std::string& origin);

/// The scene of frame k: `base` at the trajectory's pose k. Where the parameter table has `sensor.seed`,
/// its value is derived from the base seed and k (so shards reproduce a single run byte for byte).
SceneDesc frame_scene(const SceneDesc& base, const Trajectory& trajectory, size_t k);

/// "DIR/frames/NNNNNN" (6 digits).
std::string frame_prefix(const std::string& dir, size_t k);

/// A file every frame of a dataset has (`always`), or has where its scene asks for it.
struct FrameFile {
    const char* suffix;
    bool always;
};
/// The files of a frame of `scene`'s dataset: render_outputs(), or ping_outputs() for a side-scan or scan
/// (each frame one waterfall or sweep from the frame's pose, its pings along the trajectory).
std::vector<FrameFile> frame_files(const SceneDesc& scene);

/// Whether every file of frame k of the dataset of `base` in DIR exists.
bool frame_complete(const std::string& dir, size_t k, const SceneDesc& base);

/// The dataset's start when no export.start_time_s is given: 2026-01-01 00:00:00 UTC, so that the same
/// command writes the same files (`batch --start-now` asks for the wall clock instead).
constexpr double kDefaultStartTimeS = 1767225600;

/// Creates DIR and DIR/frames and writes scene.json (mesh paths made absolute), trajectory.csv and, the
/// first time, dataset.json (the start time, dataset_start_time_s; where the scene came from,
/// base.source_file; and the program that made it: name, version, commit); when DIR
/// already holds a dataset of another scene or trajectory, throws InputError (frames of two datasets are
/// never mixed). Every run renders the scene as read back from DIR, so shards, resumed runs and other
/// processes (the Dask example) render exactly the same scene.
void prepare_dataset(const std::string& dir, const SceneDesc& base, const Trajectory& trajectory);

/// True when DIR holds a dataset (its scene.json) of another scene than `base` (export keys aside): the one
/// prepare_dataset would refuse.
bool dataset_holds_other_scene(const std::string& dir, const SceneDesc& base);

/// The dataset's start, UNIX seconds of t = 0: DIR/dataset.json, which prepare_dataset writes once (from
/// base.exports.start_time_s, or kDefaultStartTimeS when that is 0); for a dataset without it, the time its
/// trajectory.csv was written. Throws InputError naming the file for a malformed one.
double dataset_start_time_s(const std::string& dir);

/// The dataset in DIR as prepare_dataset wrote it. Throws InputError when it is not one.
void load_dataset(const std::string& dir, SceneDesc& base, Trajectory& trajectory);

struct BatchProgress {
    size_t done = 0;          ///< frames of this run finished (rendered or skipped)
    size_t total = 0;         ///< frames of this run
    size_t rendered = 0;      ///< of `done`, rendered (not skipped as complete)
    double elapsed_s = 0;     ///< since the run started
    bool interrupted = false; ///< BatchOptions::stop was set: the frames after `done` were not rendered
};

struct BatchOptions {
    std::vector<size_t> frames;                         ///< which frames to render (all when empty)
    bool resume = false;                                ///< skip frames that are already complete
    std::function<void(const BatchProgress&)> progress; ///< after each frame
    bool index = true; ///< rebuild index.csv at the end (a distributed run does it once, after all tasks)
    bool ground_truth = false; ///< also write each frame's PREFIX_gt_<name>.npy (ground_truth.hpp)
    /// also write each frame's 16-bit PNG maps PREFIX_gt_<map>.png (ground_truth_files.hpp; an imaging
    /// sonar's)
    bool ground_truth_maps = false;
    /// Checked before each frame: once true (e.g. set by a SIGINT handler), no further frame is started and
    /// the run ends as if those were its last frames (the index rebuilt, BatchSummary::interrupted set).
    const std::atomic<bool>* stop = nullptr;
};

struct BatchSummary {
    size_t rendered = 0, skipped = 0; ///< frames of this run rendered, and skipped as complete (--resume)
    size_t indexed = 0;               ///< frames listed in index.csv afterwards (all shards' complete frames)
    double elapsed_s = 0;             ///< rendering, without rebuilding the index
    bool interrupted = false;         ///< stopped by BatchOptions::stop before the last frame
};

/// Renders the frames of `options` of the prepared dataset in DIR with one Simulator (the geometry is
/// built once; only the pose changes), then rebuilds index.csv (unless options.index is false).
BatchSummary run_batch(const std::string& dir, const BatchOptions& options);

/// Reads the L_EN image of frame k of the dataset in DIR (its .npy). Throws InputError(origin, ...) at
/// once when any of the first `frames` frames is not complete, or the dataset is of a side-scan or scan.
std::function<PolarImage(size_t)> dataset_images(const std::string& dir, size_t frames,
                                                 const std::string& origin);

/// Frame k of the dataset of a side-scan or scan in DIR: its scene, time and levels (its .npy). Throws
/// InputError(origin, ...) at once when any of the first `frames` frames is not complete.
PingFrameSource dataset_ping_frames(const std::string& dir, size_t frames, const std::string& origin);

/// Rebuilds DIR/index.csv from the complete frames: frame, t, pose, files (every file of the frame, ground
/// truth included), render time [ms], the sampling error estimate [dB] and rays. Returns the number of frames
/// listed.
size_t write_index(const std::string& dir, const SceneDesc& base, const Trajectory& trajectory);
/// The same for the dataset in DIR, its trajectory read from DIR.
size_t write_index(const std::string& dir);

} // namespace sonarsim

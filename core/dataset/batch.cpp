#include "core/io/ground_truth_files.hpp"
#include "core/dataset/batch.hpp"

#include "core/dataset/containers.hpp"

#include "core/base/build_info.hpp"

#include "core/sensor/sensor.hpp"

#include "core/base/errors.hpp"
#include "core/base/file_io.hpp"
#include "core/shading/ground_truth.hpp"
#include "core/io/output.hpp"
#include "core/io/ping_output.hpp"
#include "core/kinds/ping_series.hpp"
#include "core/scene/params.hpp"
#include "core/scene/scene_io.hpp"
#include "core/pipeline/simulator.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fcntl.h>
#include <filesystem>
#include <optional>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace sonarsim {
namespace {

namespace fs = std::filesystem;

/// The file's text, or "" when it cannot be read (a frame not written yet).
std::string read_text(const std::string& path) {
    return try_read_file_bytes(path).value_or("");
}

/// Holds an exclusive lock on DIR/.index.lock while alive (concurrent shards rebuild the index in turn).
class IndexLock {
  public:
    explicit IndexLock(const std::string& dir)
        : fd_(::open((dir + "/.index.lock").c_str(), O_RDWR | O_CREAT, 0644)) {
        if (fd_ >= 0) ::flock(fd_, LOCK_EX);
    }
    ~IndexLock() {
        if (fd_ >= 0) ::close(fd_); // releases the lock
    }
    IndexLock(const IndexLock&) = delete;
    IndexLock& operator=(const IndexLock&) = delete;

  private:
    int fd_;
};

std::string fmt(double v) {
    char b[40];
    std::snprintf(b, sizeof b, "%.9g", v);
    return b;
}

/// One row of index.csv for complete frame k, from its metadata JSON.
std::string index_row(const std::string& dir, const SceneDesc& scene, const Trajectory& trajectory,
                      size_t k) {
    const std::string prefix = frame_prefix(dir, k);
    const json meta = json::parse(read_text(prefix + ".json"), nullptr, false);
    const TrajectoryPoint& p = trajectory[k];
    std::string files;
    std::error_code ec;
    auto add = [&](const std::string& path) {
        files += (files.empty() ? "" : ";") + fs::path(path).lexically_relative(dir).string();
    };
    for (const FrameFile& f : frame_files(scene))
        if (f.always || fs::is_regular_file(prefix + f.suffix, ec)) add(prefix + f.suffix);
    for (auto& name : ground_truth_names()) // batch --ground-truth
        if (fs::is_regular_file(prefix + "_gt_" + name + ".npy", ec)) add(prefix + "_gt_" + name + ".npy");
    for (const GroundTruthMap& m : ground_truth_maps(scene)) // batch --ground-truth-png
        if (fs::is_regular_file(prefix + "_gt_" + m.name + ".png", ec))
            add(prefix + "_gt_" + m.name + ".png");
    std::string ms, err_median, err_p95, rays;
    if (meta.is_object()) {
        if (meta.contains("time_ms")) ms = fmt(meta["time_ms"].value("total", 0.0));
        if (meta.contains("render_ms")) ms = fmt(meta.value("render_ms", 0.0)); // a side-scan's or scan's
        const json est = meta.value("sampling_error_estimate", json());
        if (est.is_object())
            err_median = fmt(est.value("median_abs_db", 0.0)), err_p95 = fmt(est.value("p95_abs_db", 0.0));
        if (meta.contains("rays_traced")) rays = meta["rays_traced"].dump();
    }
    const Vec3d &x = p.pose.position_m, &o = p.pose.orientation_deg;
    return std::to_string(k) + "," + fmt(p.t_s) + "," + fmt(x[0]) + "," + fmt(x[1]) + "," + fmt(x[2]) + "," +
           fmt(o[0]) + "," + fmt(o[1]) + "," + fmt(o[2]) + "," + files + "," + ms + "," + err_median + "," +
           err_p95 + "," + rays + "\n";
}

} // namespace

std::vector<size_t> shard_frames(const std::string& spec, size_t total, const std::string& origin) {
    const size_t slash = spec.find('/');
    long long i = -1, n = 0;
    try {
        size_t a = 0, b = 0;
        if (slash != std::string::npos) {
            i = std::stoll(spec.substr(0, slash), &a);
            n = std::stoll(spec.substr(slash + 1), &b);
        }
        if (a != slash || b != spec.size() - slash - 1) n = 0;
    } catch (...) {
        n = 0;
    }
    if (n < 1 || i < 0 || i >= n)
        throw InputError(origin, "", "\"" + spec + "\": expected i/n with 0 <= i < n, e.g. 0/4");
    std::vector<size_t> frames;
    for (size_t k = size_t(i); k < total; k += size_t(n)) frames.push_back(k);
    return frames;
}

SceneDesc frame_scene(const SceneDesc& base, const Trajectory& trajectory, size_t k) {
    SceneDesc s = base;
    s.sonar.pose = trajectory.at(k).pose;
    if (base.sonar.motion_from_trajectory) set_motion_from_trajectory(s.sonar, trajectory, k);
    // Each frame its own speckle and noise, reproducible from the base seed and the frame number alone (so
    // shards and resumed runs give the same bytes as one run).
    const ParamSpec& seed = *find_param("sensor.seed");
    const auto span = std::uint64_t(seed.max - seed.min + 1);
    const auto value = std::int64_t(seed.min) +
                       std::int64_t(mix64(std::uint64_t(base.sensor.seed) * 0x100000001b3ull + k) % span);
    apply_setting(s, "sensor.seed", json(value), "batch frame " + std::to_string(k));
    return s;
}

std::string frame_prefix(const std::string& dir, size_t k) {
    char name[32];
    std::snprintf(name, sizeof name, "%06zu", k);
    return (fs::path(dir) / "frames" / name).string();
}

std::vector<FrameFile> frame_files(const SceneDesc& scene) {
    std::vector<FrameFile> files;
    if (scene.sonar.kind == SonarKind::Imaging)
        for (auto& o : render_outputs()) files.push_back({o.suffix, !o.wanted});
    else
        for (auto& o : ping_outputs()) files.push_back({o.suffix, !o.wanted});
    return files;
}

bool frame_complete(const std::string& dir, size_t k, const SceneDesc& scene) {
    // A frame's files are renamed into place as one set: the files every frame has tell.
    std::error_code ec;
    for (const FrameFile& f : frame_files(scene))
        if (f.always && !fs::is_regular_file(frame_prefix(dir, k) + f.suffix, ec)) return false;
    return true;
}

namespace {

/// The scene file text a dataset stores: mesh paths absolute.
std::string stored_scene_text(const SceneDesc& base) {
    SceneDesc stored = base;
    for (auto& o : stored.objects)
        if (!o.mesh_resolved.empty())
            o.mesh_resolved = fs::absolute(o.mesh_resolved).lexically_normal().string();
    return scene_to_json(stored).dump(2) + "\n";
}

/// Whether two of a dataset's files say the same: the export keys choose how a dataset is packed, not what
/// it holds, so they may differ between runs.
bool same_content(const std::string& path, const std::string& a, const std::string& b) {
    if (path.size() < 5 || path.compare(path.size() - 5, 5, ".json") != 0) return a == b;
    json x = json::parse(a, nullptr, false), y = json::parse(b, nullptr, false);
    if (x.is_object()) x.erase("export");
    if (y.is_object()) y.erase("export");
    return x == y;
}

} // namespace

bool dataset_holds_other_scene(const std::string& dir, const SceneDesc& base) {
    const std::string path = dir + "/scene.json";
    std::error_code ec;
    return fs::exists(path, ec) && !same_content(path, read_text(path), stored_scene_text(base));
}

void prepare_dataset(const std::string& dir, const SceneDesc& base, const Trajectory& trajectory) {
    std::error_code ec;
    fs::create_directories(fs::path(dir) / "frames", ec);
    if (ec) throw InputError(dir, "", "cannot create the dataset directory: " + ec.message());
    const std::string scene_text = stored_scene_text(base);
    const std::string traj_text = trajectory_to_csv(trajectory);
    const std::string scene_path = dir + "/scene.json", traj_path = dir + "/trajectory.csv";
    for (auto [path, text] : {std::pair{scene_path, scene_text}, std::pair{traj_path, traj_text}})
        if (fs::exists(path, ec) && !same_content(path, read_text(path), text))
            throw InputError(dir, "",
                             "holds a dataset of another scene or trajectory (" + path +
                                 " differs); choose another directory");
    std::vector<std::pair<std::string, std::vector<std::uint8_t>>> files = {
        {scene_path, to_bytes(scene_text)}, {traj_path, to_bytes(traj_text)}};
    // The dataset's start (UNIX s of t = 0), fixed when it is first prepared so that resumed runs agree.
    const std::string start_path = dir + "/dataset.json";
    if (!fs::exists(start_path, ec)) {
        const double start = base.exports.start_time_s > 0 ? base.exports.start_time_s : kDefaultStartTimeS;
        const json provenance = {
            {"start_time_s", start},
            {"scene_file", base.source_file.empty()
                               ? json(nullptr)
                               : json(fs::absolute(base.source_file).lexically_normal().string())},
            {"program",
             {{"name", "sonarsim"}, {"version", program_version()}, {"commit", program_commit()}}}};
        files.push_back({start_path, to_bytes(provenance.dump(2) + "\n")});
    }
    write_files_atomically(files);
}

double dataset_start_time_s(const std::string& dir) {
    const std::string path = dir + "/dataset.json";
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) { // a dataset of an earlier version: when it was prepared
        struct stat st {};
        return ::stat((dir + "/trajectory.csv").c_str(), &st) == 0 ? double(st.st_mtime) : 0.0;
    }
    const json j = json::parse(read_text(path), nullptr, false);
    if (!j.is_object() || !j.contains("start_time_s") || !j["start_time_s"].is_number() ||
        !(j["start_time_s"].get<double>() >= 0))
        throw InputError(path, "start_time_s", "not a UNIX time in seconds (>= 0)");
    return j["start_time_s"].get<double>();
}

void load_dataset(const std::string& dir, SceneDesc& base, Trajectory& trajectory) {
    const std::string scene_path = dir + "/scene.json", traj_path = dir + "/trajectory.csv";
    std::error_code ec;
    if (!fs::is_regular_file(scene_path, ec) || !fs::is_regular_file(traj_path, ec))
        throw InputError(dir, "", "not a dataset of `sonarsim batch` (no scene.json or trajectory.csv)");
    base = parse_scene(read_text(scene_path), scene_path, dir);
    trajectory = load_trajectory_csv(traj_path);
}

BatchSummary run_batch(const std::string& dir, const BatchOptions& options) {
    SceneDesc base;
    Trajectory trajectory;
    load_dataset(dir, base, trajectory);
    std::vector<size_t> frames = options.frames;
    if (frames.empty())
        for (size_t k = 0; k < trajectory.size(); ++k) frames.push_back(k);
    const auto t0 = std::chrono::steady_clock::now();
    std::optional<Simulator> sim; // built at the first frame to render: the geometry once for all frames
    BatchProgress progress;
    progress.total = frames.size();
    for (const size_t k : frames) {
        if (options.stop && options.stop->load()) {
            progress.interrupted = true;
            break;
        }
        if (!(options.resume && frame_complete(dir, k, base))) {
            const SceneDesc s = frame_scene(base, trajectory, k);
            if (s.sonar.kind != SonarKind::Imaging) { // a side-scan's waterfall or a scan's sweep
                PingControl control;
                control.ground_truth = options.ground_truth;
                write_ping_files(frame_prefix(dir, k), s, render_pings(s, control));
            } else {
                if (sim)
                    sim->set_scene(s);
                else
                    sim.emplace(s);
                const bool truth = options.ground_truth || options.ground_truth_maps;
                sim->request({truth, false});
                const auto f = sim->render();
                const std::string prefix = frame_prefix(dir, k);
                GroundTruthOutputs gt;
                if (truth)
                    gt = ground_truth_outputs(prefix, *f->truth_ptr, s, options.ground_truth,
                                              options.ground_truth_maps);
                write_render_files(prefix, s, *f, std::move(gt.files), gt.metadata);
            }
            ++progress.rendered;
        }
        ++progress.done;
        progress.elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (options.progress) options.progress(progress);
    }
    BatchSummary summary;
    summary.rendered = progress.rendered;
    summary.skipped = progress.done - progress.rendered;
    summary.elapsed_s = progress.elapsed_s;
    summary.interrupted = progress.interrupted;
    if (options.index) summary.indexed = write_index(dir, base, trajectory);
    return summary;
}

namespace {

/// Throws InputError(origin, ...) at once when any of the first `frames` frames is not complete.
void check_frames_complete(const std::string& dir, size_t frames, const SceneDesc& base,
                           const std::string& origin) {
    for (size_t k = 0; k < frames; ++k)
        if (!frame_complete(dir, k, base))
            throw InputError(
                origin, "",
                "frame " + std::to_string(k) + " of " + dir +
                    " is not complete; when every shard has finished, run `batch --resume` with it");
}

} // namespace

PingFrameSource dataset_ping_frames(const std::string& dir, size_t frames, const std::string& origin) {
    SceneDesc base;
    Trajectory trajectory;
    load_dataset(dir, base, trajectory);
    check_frames_complete(dir, frames, base, origin);
    return [dir, base, trajectory](size_t k) {
        PingFrame f;
        f.scene = frame_scene(base, trajectory, k);
        f.t_s = trajectory.at(k).t_s;
        const size_t values = ping_schedule(f.scene).size() * size_t(channel_count(base.sonar.kind)) *
                              size_t(base.sonar.range_bins);
        const std::string path = frame_prefix(dir, k) + ".npy";
        const std::string bytes = read_text(path);
        f.level_db = decode_npy_values(Bytes(bytes.begin(), bytes.end()), path, values);
        return f;
    };
}

std::function<PolarImage(size_t)> dataset_images(const std::string& dir, size_t frames,
                                                 const std::string& origin) {
    SceneDesc base;
    Trajectory trajectory;
    load_dataset(dir, base, trajectory);
    if (base.sonar.kind != SonarKind::Imaging)
        throw InputError(
            origin, "sonar.kind",
            "the dataset in " + dir + " holds a " + kind_name(base.sonar.kind) +
                " sonar's pings, not an imaging sonar's frames; allowed: " + containers_for(base.sonar.kind));
    check_frames_complete(dir, frames, base, origin);
    return [dir](size_t k) {
        const std::string path = frame_prefix(dir, k) + ".npy";
        const std::string bytes = read_text(path);
        return decode_npy(Bytes(bytes.begin(), bytes.end()), path);
    };
}

size_t write_index(const std::string& dir, const SceneDesc& base, const Trajectory& trajectory) {
    IndexLock lock(dir);
    std::string text =
        "frame,t,x,y,z,roll_deg,pitch_deg,yaw_deg,files,ms,error_median_db,error_p95_db,rays\n";
    size_t listed = 0;
    for (size_t k = 0; k < trajectory.size(); ++k)
        if (frame_complete(dir, k, base)) text += index_row(dir, base, trajectory, k), ++listed;
    write_files_atomically({{dir + "/index.csv", to_bytes(text)}});
    return listed;
}

} // namespace sonarsim

namespace sonarsim {

size_t write_index(const std::string& dir) {
    SceneDesc base;
    Trajectory trajectory;
    load_dataset(dir, base, trajectory);
    return write_index(dir, base, trajectory);
}

} // namespace sonarsim

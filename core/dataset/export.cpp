#include "core/dataset/export.hpp"

#include "core/dataset/batch.hpp"
#include "core/io/output.hpp"
#include "core/scene/params.hpp"
#include "core/base/errors.hpp"

#include <filesystem>
#include <stdexcept>

namespace sonarsim {

ExportReport export_dataset(const std::string& dir, const std::string& path,
                            const DatasetContainer& container, bool float32, const ExportParams& exports,
                            const std::string& origin) {
    if (float32 && !container.holds_float32)
        throw std::invalid_argument(std::string("export_dataset: an ") + container.name + " holds bytes");
    SceneDesc scene; // the files describe the dataset as rendered
    Trajectory poses;
    load_dataset(dir, scene, poses);
    check_holds(container, scene, origin);
    scene.exports = exports;
    if (!(scene.exports.start_time_s > 0)) scene.exports.start_time_s = dataset_start_time_s(dir);
    ContainerJob job;
    job.path = path, job.origin = origin;
    job.times_origin = (std::filesystem::path(dir) / "trajectory.csv").string();
    job.type = float32 ? SonarDataType::Float32 : SonarDataType::Uint8;
    ExportReport report;
    if (scene.sonar.kind != SonarKind::Imaging) {
        const PingFrameSource frames = dataset_ping_frames(dir, poses.size(), origin);
        auto start = [&](PingFrame f) { // on the clock of the export keys given
            f.scene.exports.start_time_s = scene.exports.start_time_s;
            return f;
        };
        if (!float32)
            job.mapping = choose_byte_mapping(exports, poses.size(), [&](size_t k) {
                PingFrame f = frames(k);
                PolarImage img; // every sample of the frame's pings
                img.bins = 1, img.beams = int(f.level_db.size());
                img.level_db = std::move(f.level_db);
                return img;
            });
        report = container.write_pings(job, poses.size(), [&](size_t k) { return start(frames(k)); });
    } else {
        const FrameImageSource images = dataset_images(dir, poses.size(), origin);
        if (!float32) job.mapping = choose_byte_mapping(exports, poses.size(), images);
        report = container.write_frames(job, scene, poses, images);
    }
    if (!float32)
        write_files_atomically(
            {{path + ".json",
              to_bytes(report.to_json(std::filesystem::path(path).filename().string()).dump(2) + "\n")}});
    return report;
}

} // namespace sonarsim

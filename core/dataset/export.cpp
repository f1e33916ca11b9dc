#include "core/dataset/export.hpp"

#include "core/dataset/batch.hpp"
#include "core/io/aris.hpp"
#include "core/io/output.hpp"
#include "core/io/ros2_pings.hpp"
#include "core/io/ros2_sonar.hpp"
#include "core/scene/params.hpp"
#include "core/base/errors.hpp"

#include <filesystem>

namespace sonarsim {

ExportReport export_dataset(const std::string& dir, const std::string& path, ExportFormat format,
                            const ExportParams& exports, const std::string& origin) {
    SceneDesc scene; // the files describe the dataset as rendered
    Trajectory poses;
    load_dataset(dir, scene, poses);
    scene.exports = exports;
    if (!(scene.exports.start_time_s > 0)) scene.exports.start_time_s = dataset_start_time_s(dir);
    const bool bytes = format != ExportFormat::McapFloat32;
    ExportReport report;
    if (scene.sonar.kind != SonarKind::Imaging) {
        if (format == ExportFormat::Aris)
            throw InputError(origin, "sonar.kind",
                             "an ARIS recording holds an imaging sonar's frames, not a " +
                                 kind_name(scene.sonar.kind) +
                                 " sonar's pings; allowed: --mcap (each frame also has its own " +
                                 (scene.sonar.kind == SonarKind::Sidescan ? ".xtf" : "_ping360.bin") + ")");
        const PingFrameSource frames = dataset_ping_frames(dir, poses.size(), origin);
        auto start = [&](PingFrame f) { // on the clock of the export keys given
            f.scene.exports.start_time_s = scene.exports.start_time_s;
            return f;
        };
        const ByteMapping mapping =
            bytes ? choose_byte_mapping(exports, poses.size(),
                                        [&](size_t k) {
                                            PingFrame f = frames(k);
                                            PolarImage img; // every sample of the frame's pings
                                            img.bins = 1, img.beams = int(f.level_db.size());
                                            img.level_db = std::move(f.level_db);
                                            return img;
                                        })
                  : ByteMapping{};
        report = write_ping_mcap(
            path, poses.size(), [&](size_t k) { return start(frames(k)); },
            bytes ? SonarDataType::Uint8 : SonarDataType::Float32, mapping);
    } else {
        if (format == ExportFormat::Aris)
            check_aris_frame_times(scene, poses, origin,
                                   (std::filesystem::path(dir) / "trajectory.csv").string());
        const FrameImageSource images = dataset_images(dir, poses.size(), origin);
        const ByteMapping mapping =
            bytes ? choose_byte_mapping(exports, poses.size(), images) : ByteMapping{};
        report = format == ExportFormat::Aris
                     ? write_aris(path, scene, poses, images, mapping, origin)
                     : write_sonar_mcap(path, scene, poses, images,
                                        bytes ? SonarDataType::Uint8 : SonarDataType::Float32, mapping);
    }
    if (bytes)
        write_files_atomically(
            {{path + ".json",
              to_bytes(report.to_json(std::filesystem::path(path).filename().string()).dump(2) + "\n")}});
    return report;
}

} // namespace sonarsim

#include "core/dataset/export.hpp"

#include "core/dataset/batch.hpp"
#include "core/io/aris.hpp"
#include "core/io/output.hpp"
#include "core/io/ros2_sonar.hpp"

#include <filesystem>

namespace sonarsim {

ExportReport export_dataset(const std::string& dir, const std::string& path, ExportFormat format,
                            const ExportParams& exports, const std::string& origin) {
    SceneDesc scene; // the files describe the dataset as rendered
    Trajectory poses;
    load_dataset(dir, scene, poses);
    scene.exports = exports;
    if (!(scene.exports.start_time_s > 0)) scene.exports.start_time_s = dataset_start_time_s(dir);
    if (format == ExportFormat::Aris)
        check_aris_frame_times(scene, poses, origin,
                               (std::filesystem::path(dir) / "trajectory.csv").string());
    const FrameImageSource images = dataset_images(dir, poses.size(), origin);
    const bool bytes = format != ExportFormat::McapFloat32;
    const ByteMapping mapping = bytes ? choose_byte_mapping(exports, poses.size(), images) : ByteMapping{};
    ExportReport report;
    if (format == ExportFormat::Aris)
        report = write_aris(path, scene, poses, images, mapping, origin);
    else
        report = write_sonar_mcap(path, scene, poses, images,
                                  bytes ? SonarDataType::Uint8 : SonarDataType::Float32, mapping);
    if (bytes)
        write_files_atomically(
            {{path + ".json",
              to_bytes(report.to_json(std::filesystem::path(path).filename().string()).dump(2) + "\n")}});
    return report;
}

} // namespace sonarsim

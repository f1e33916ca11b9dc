// The files of a side-scan's or scanning sonar's image, in one table: the waterfall or sweep PNG, the raw
// arrays (.npy float32), and the metadata (every effective parameter, each ping's time, pose, head angle and
// first bottom return).
#pragma once
#include "core/io/byte_mapping.hpp"
#include "core/io/png.hpp"
#include "core/kinds/ping_series.hpp"
#include "core/scene/param_spec.hpp"

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace sonarsim {

/// What the files of a ping image share, made once per write: the levels the image shows (the waterfall, or
/// the scan's raw array), the display range it is shown with, and the 8-bit files' byte mapping.
struct PingViews {
    PolarImage shown;
    DisplayParams display;
    ByteMapping mapping;
};
PingViews ping_views(const SceneDesc& scene, const PingSeries& series);

/// One file of a ping image: PREFIX + suffix.
struct PingOutput {
    const char* suffix;
    const char* what;
    Bytes (*encode)(const SceneDesc& scene, const PingSeries& series, const PingViews& views);
    bool (*wanted)(const SceneDesc& scene) = nullptr; ///< written only where it says so (null: always)
    /// The recording format of this kind's devices (XTF for side-scan, the Ping Viewer log for a scan),
    /// which each frame of a dataset has as well; nullopt for the others.
    std::optional<SonarKind> recording_of = std::nullopt;
};

/// The one table of the files a side-scan or scanning image is written as.
const std::vector<PingOutput>& ping_outputs();

/// "PREFIX.png (waterfall ...), ...": the files `scene` writes, for messages.
std::string ping_outputs_text(const std::string& prefix, const SceneDesc& scene);

/// Writes every file of ping_outputs() for `prefix`, the series' ground truth when it has one
/// (ping_ground_truth_files) and the `extra` files (a 3D view PNG), in one atomic step. Returns the paths.
std::vector<std::string> write_ping_files(const std::string& prefix, const SceneDesc& scene,
                                          const PingSeries& series,
                                          std::vector<std::pair<std::string, Bytes>> extra = {});

/// PREFIX_gt_<name>.npy of a series made with PingControl::ground_truth, each of the .npy's shape (pings,
/// channels, bins; a scan's (steps, bins)), point_m with a last axis of 3; none without.
std::vector<std::pair<std::string, Bytes>> ping_ground_truth_files(const std::string& prefix,
                                                                   const PingSeries& series);

/// The 8-bit files' mapping of a series' levels (.xtf, _ping360.bin): export.lo_db/hi_db, or with export.auto
/// the high quantile of every ping's levels (choose_byte_mapping, each ping one image).
ByteMapping ping_byte_mapping(const SceneDesc& scene, const PingSeries& series);

/// The ping image as the PNG shows it: a side-scan's waterfall, a scanning sonar's sweep.
Image8 ping_image(const SceneDesc& scene, const PingSeries& series, const PingViews& views);

/// Metadata: the scene's parameters, the sound speed and ping interval, the bin edges, and per ping its
/// time, vehicle pose, head angle (scanning) and first bottom return (side-scan).
json ping_metadata(const SceneDesc& scene, const PingSeries& series, const PingViews& views);

} // namespace sonarsim

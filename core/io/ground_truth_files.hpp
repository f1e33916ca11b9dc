// The ground truth's files: one NumPy array per field (shading/ground_truth.hpp), as render, batch and the
// viewer's snapshots write them; and 16-bit PNG maps of the range and elevation that image tools open.
#pragma once
#include "core/io/output.hpp"
#include "core/shading/ground_truth.hpp"

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace sonarsim {

/// PREFIX_gt_<name>.npy for each array (float32, int32 for object_id and surfaces), shape (bins, beams).
std::vector<std::pair<std::string, Bytes>> ground_truth_files(const std::string& prefix,
                                                              const GroundTruth& gt);

/// The same for `parts` laid end to end (a side-scan's or scan's pings and channels, each (bins, 1)), as
/// arrays of shape `shape` (e.g. pings, channels, bins), point_m with a last axis of 3.
std::vector<std::pair<std::string, Bytes>> ground_truth_files(const std::string& prefix,
                                                              const std::vector<GroundTruth>& parts,
                                                              const std::vector<std::size_t>& shape);

/// One 16-bit map of the ground truth, PREFIX_gt_<name>.png, laid out as PREFIX_polar.png (range bins
/// upward, the nearest at the bottom; beams from port on the left): pixel value v is 0 where nothing echoes,
/// else the quantity offset + (v - 1) * scale [unit].
struct GroundTruthMap {
    std::string name; ///< range_m, elevation_deg: the GroundTruth array it maps
    std::vector<float> GroundTruth::*field;
    std::string unit, what;
    double offset = 0, scale = 1;
};

/// The maps of `scene`'s images: GroundTruth::range_m, 0 to 2 sonar.range_max_m (a multipath echo spread over
/// its footprint may put its scatterer's distance a little past the bin, and past the window's end: twice the
/// window leaves room); elevation_deg, -90 to 90.
std::vector<GroundTruthMap> ground_truth_maps(const SceneDesc& scene);

/// PREFIX_gt_<name>.png of each map, each with tEXt chunks saying what it holds and its scale.
std::vector<std::pair<std::string, Bytes>>
ground_truth_map_files(const std::string& prefix, const GroundTruth& gt, const SceneDesc& scene);

/// What a frame's ground truth adds to its files: the arrays (ground_truth_files) and the maps
/// (ground_truth_map_files), as asked, and the keys the maps add to the metadata (null without maps).
struct GroundTruthOutputs {
    std::vector<std::pair<std::string, Bytes>> files;
    json metadata;
};
GroundTruthOutputs ground_truth_outputs(const std::string& prefix, const GroundTruth& gt,
                                        const SceneDesc& scene, bool arrays, bool maps);

/// The maps' descriptions for the metadata: {"ground_truth_maps": [{suffix (PREFIX + it is the file),
/// quantity, unit, offset, scale, zero, layout}, ...]}.
json ground_truth_maps_metadata(const SceneDesc& scene);

} // namespace sonarsim

// The ground truth's files: one NumPy array per field (shading/ground_truth.hpp), as render, batch and the
// viewer's snapshots write them.
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

} // namespace sonarsim

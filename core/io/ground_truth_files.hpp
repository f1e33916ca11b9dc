// The ground truth's files: one NumPy array per field (shading/ground_truth.hpp), as render, batch and the
// viewer's snapshots write them.
#pragma once
#include "core/io/output.hpp"
#include "core/shading/ground_truth.hpp"

#include <string>
#include <utility>
#include <vector>

namespace sonarsim {

/// PREFIX_gt_<name>.npy for each array (float32, int32 for object_id and surfaces).
std::vector<std::pair<std::string, Bytes>> ground_truth_files(const std::string& prefix,
                                                              const GroundTruth& gt);

} // namespace sonarsim

// A complete dataset packed into one file for practitioners' tools: a row of dataset_containers() (an ARIS
// recording, a ROS 2 bag in MCAP). The 8-bit ones map levels to bytes once for the whole dataset
// (io/byte_mapping.hpp) and write beside the file FILE.json: the mapping and what it clipped, per frame and
// in all.
#pragma once
#include "core/dataset/containers.hpp"
#include "core/io/byte_mapping.hpp"
#include "core/data/scene.hpp"

#include <string>

namespace sonarsim {

/// Writes the complete dataset in DIR as `path` in `container` (its frames read one at a time, twice under
/// export.auto: once for the mapping, once to write), float32 levels in dB when `float32` (a container that
/// holds them) else bytes under the mapping of `exports` (the caller's export.* keys: they do not change the
/// dataset), then `path`.json. Throws InputError(origin, ...) when a frame is missing, the container does not
/// hold the dataset's kind, or (ARIS) the beam count is not one ARIS has.
ExportReport export_dataset(const std::string& dir, const std::string& path,
                            const DatasetContainer& container, bool float32, const ExportParams& exports,
                            const std::string& origin);

} // namespace sonarsim

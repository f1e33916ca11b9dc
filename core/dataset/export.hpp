// A complete dataset packed into one file for practitioners' tools: an ARIS recording or a ROS 2 bag in MCAP.
// The 8-bit ones map levels to bytes once for the whole dataset (io/byte_mapping.hpp) and write beside the
// file FILE.json: the mapping and what it clipped, per frame and in all.
#pragma once
#include "core/io/byte_mapping.hpp"
#include "core/data/scene.hpp"

#include <string>

namespace sonarsim {

enum class ExportFormat { Aris, McapUint8, McapFloat32 };

/// Writes the complete dataset in DIR as `path` (its frames read one at a time, twice under export.auto:
/// once for the mapping, once to write), with the mapping of `exports` (the caller's export.* keys: they
/// do not change the dataset), and for the 8-bit formats `path`.json. Throws InputError(origin, ...) when a
/// frame is missing or (ARIS) the beam count is not one ARIS has.
ExportReport export_dataset(const std::string& dir, const std::string& path, ExportFormat format,
                            const ExportParams& exports, const std::string& origin);

} // namespace sonarsim

// Side-scan pings as an XTF file (eXtended Triton Format, Rev. 41 layout as SIDESCAN_SCANNING.md 3 gives
// it): a 1024-byte file header with two CHANINFO blocks (port, starboard), then per ping one sonar record:
// XTFPINGHEADER (256 bytes), and per channel an XTFPINGCHANHEADER (64 bytes) and its samples. Packed
// little-endian. The reader (xtf_read.hpp) is written from the same published layout.
#pragma once
#include "core/io/byte_mapping.hpp"
#include "core/io/png.hpp"
#include "core/kinds/ping_series.hpp"

namespace sonarsim {

/// The XTF file of a side-scan's pings: each sample one byte of its level under `mapping` (the 8-bit
/// exports' mapping, written into the file header's note), nearest sample first in both channels; times
/// from export.start_time_s plus each ping's time; positions in metres (NavUnits 0: x east, y north as the
/// scene's x and y), heading clockwise from north (90 - yaw), the first bottom return as the altitude.
Bytes encode_xtf(const SceneDesc& scene, const PingSeries& series, const ByteMapping& mapping);

} // namespace sonarsim

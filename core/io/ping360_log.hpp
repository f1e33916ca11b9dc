// A scanning sonar's sweep as a Ping Viewer sensor log (.bin), the file Blue Robotics' Ping Viewer records
// and replays for the Ping360 (docs/formats.md): a big-endian header (Qt QDataStream: strings as a uint32
// byte count and UTF-16 text, int32 numbers), then per step a timestamp string and one ping-protocol message
// `device_data` (id 2300, little-endian: "BR", payload length, id, source and destination, payload, byte-sum
// checksum). The reader (ping360_log_read.hpp) is written from the same published descriptions.
#pragma once
#include "core/io/byte_mapping.hpp"
#include "core/io/png.hpp"
#include "core/kinds/ping_series.hpp"

#include <string>

namespace sonarsim {

/// Why the sweep cannot be a Ping360 log (a value outside the protocol's fields: frequency 500-1000 kHz,
/// 200-1200 samples over [0, r_max), a sample period of 80-40000 ticks of 25 ns), or "" when it can.
std::string ping360_log_problem(const SceneDesc& scene);

/// The Ping Viewer log of a scanning sonar's sweep: per step, `device_data` with the head angle in gradians
/// (clockwise from the sonar's forward axis seen from above), the samples over [0, r_max) (the bins
/// resampled; 0 before r_min) as bytes under `mapping`, the transmit duration of the viewer's automatic rule
/// (8000 R / c us, within [5, 500] us and 64 sample periods), the time of day of export.start_time_s plus the
/// step's time. Throws InputError(origin, key, ...) where ping360_log_problem says why not.
Bytes encode_ping360_log(const SceneDesc& scene, const PingSeries& series, const ByteMapping& mapping,
                         const std::string& origin);

} // namespace sonarsim

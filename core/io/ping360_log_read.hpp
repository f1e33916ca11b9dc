// Reading Ping Viewer sensor logs (.bin) of a Ping360: the big-endian header (strings as a uint32 byte count
// and UTF-16 text, int32 numbers), then records of a timestamp string and one ping-protocol message, of which
// `device_data` (2300) is decoded. Written from Ping Viewer's published log structure and the ping-protocol
// message definitions (docs/formats.md), apart from our writer; every malformed file is an InputError naming
// the file and the field.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace sonarsim {

struct Ping360DeviceData {
    std::string timestamp; ///< "hh:mm:ss.zzz"
    int mode = 0, gain_setting = 0;
    int angle_grad = 0; ///< 0-399
    int transmit_duration_us = 0;
    int sample_period_ticks = 0; ///< 25 ns each
    int transmit_frequency_khz = 0;
    int number_of_samples = 0;
    std::vector<std::uint8_t> data; ///< echo strength, nearest sample first
};

struct Ping360Log {
    std::string header; ///< "PingViewer sensor log file"
    int version = 0, sensor_family = 0, sensor_type = 0;
    std::vector<std::string> build_info; ///< hash, date, tag, OS name, OS version
    std::vector<Ping360DeviceData> pings;
};

/// Parses a log's bytes (messages other than 2300 are skipped); throws InputError(`path`, field, ...).
Ping360Log read_ping360_log(const std::vector<std::uint8_t>& bytes, const std::string& path);

} // namespace sonarsim

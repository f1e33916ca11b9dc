// Reading XTF side-scan files (eXtended Triton Format): the file header with its channel blocks, then the
// sonar records (header type 0), each a ping header and per channel a header and its samples. Written from
// the published layout (SIDESCAN_SCANNING.md 3, pyxtf's structures), apart from our writer (xtf.cpp); every
// malformed file is an InputError naming the file and the field.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace sonarsim {

struct XtfChannelInfo {
    int type = 0;             ///< TypeOfChannel: 1 port, 2 starboard
    int bytes_per_sample = 0; ///< BytesPerSample
    std::string name;         ///< ChannelName
    float frequency_khz = 0, horizontal_beam_deg = 0, tilt_deg = 0, beam_width_deg = 0;
};

struct XtfChannelPing {
    int channel = 0;                             ///< ChannelNumber
    float slant_range_m = 0, ground_range_m = 0; ///< SlantRange, GroundRange
    float time_delay_s = 0, time_duration_s = 0; ///< TimeDelay, TimeDuration
    float seconds_per_ping = 0;                  ///< SecondsPerPing
    std::uint32_t samples = 0;                   ///< NumSamples
    std::vector<std::uint8_t> data;              ///< samples x bytes per sample, as stored
    /// The same samples nearest the towfish first: a port channel's (TypeOfChannel 1) are stored far first
    /// (the specification, Rev. 41, 2.3.1: odd-numbered sonar channels are reversed for the waterfall).
    std::vector<std::uint8_t> near_first;
};

struct XtfPing {
    int year = 0, month = 0, day = 0, hour = 0, minute = 0, second = 0, hundredths = 0, julian_day = 0;
    std::uint32_t ping_number = 0;
    float sound_velocity = 0, computed_sound_velocity = 0;
    double sensor_x = 0, sensor_y = 0; ///< SensorXcoordinate, SensorYcoordinate
    float altitude_m = 0, depth_m = 0, pitch_deg = 0, roll_deg = 0, heading_deg = 0;
    std::vector<XtfChannelPing> channels;
};

struct XtfFile {
    std::string recording_program, sonar_name, note;
    int nav_units = 0, sonar_channels = 0;
    std::vector<XtfChannelInfo> channel_info;
    std::vector<XtfPing> pings; ///< the sonar records, in file order (other record types are skipped)
};

/// Parses an XTF file's bytes; throws InputError(`path`, field, ...) when it is not one.
XtfFile read_xtf(const std::vector<std::uint8_t>& bytes, const std::string& path);

} // namespace sonarsim

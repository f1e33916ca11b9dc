// Reading Sound Metrics ARIS recordings (.aris, DDF_05): the file header, then per frame a 1024-byte header
// and BeamCount x SamplesPerBeam bytes, sample-major. Written from the vendor's published header layout
// (docs/formats.md), independently of our writer (aris.cpp). For comparing real recordings with simulated
// frames (`sonarsim compare`); every malformed file is an InputError naming the file and the field.
#pragma once
#include "core/data/polar_image.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace sonarsim {

/// What a frame header says about the frame's geometry and the sonar, in SI units.
struct ArisFrameInfo {
    std::uint32_t index = 0;          ///< FrameIndex
    std::uint64_t time_us = 0;        ///< FrameTime, microseconds since 1970
    std::uint32_t ping_mode = 0;      ///< PingMode (1: 48 beams, 3: 96, 6: 64, 9: 128)
    bool high_frequency = false;      ///< FrequencyHiLow
    int beams = 0, samples = 0;       ///< BeamCount (from PingMode), SamplesPerBeam
    double sample_period_us = 0;      ///< SamplePeriod
    double sample_start_delay_us = 0; ///< SampleStartDelay
    double sound_speed_m_s = 0;       ///< SoundSpeed
    double window_start_m = 0;        ///< range of sample 0's start: c SampleStartDelay / 2
    double sample_length_m = 0;       ///< c SamplePeriod / 2
    double receiver_gain_db = 0;      ///< ReceiverGain
    double position_m[3] = {0, 0, 0}; ///< SonarX, SonarY, SonarZ
};

struct ArisFrame {
    ArisFrameInfo info;
    /// The samples as levels: rows = samples (row 0 nearest), columns = beams with column 0 the port-most
    /// (ARIS beam 0 is the starboard-most); byte b is b x 80 / 255 dB above the device's floor (its 0-80 dB
    /// display mapping), byte 0 is -inf (nothing above the floor).
    PolarImage level_db;
};

/// Beams of an ARIS ping mode; 0 for a mode we do not know.
int aris_beams_of_ping_mode(std::uint32_t ping_mode);

/// The number of frames in `path` (from its size, as the format's notes tell readers to).
std::size_t aris_frame_count(const std::string& path);

/// Frame `k` of `path`. Throws InputError(path, field, ...) for a file that is not a DDF_05 recording, a
/// frame out of range, or header fields that contradict each other or the file's size.
ArisFrame read_aris_frame(const std::string& path, std::size_t k);

/// The same from bytes already in memory (`origin` names them in errors); used by the file reader and the
/// fuzz target.
ArisFrame parse_aris_frame(const std::vector<std::uint8_t>& bytes, std::size_t k, const std::string& origin);
std::size_t aris_frame_count(const std::vector<std::uint8_t>& bytes, const std::string& origin);

} // namespace sonarsim

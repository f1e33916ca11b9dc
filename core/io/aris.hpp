// Sound Metrics ARIS recordings (.aris, SENSORS.md §3.1 and Appendix A): a 1024-byte file header, then per
// frame a 1024-byte frame header and BeamCount x SamplesPerBeam bytes, sample-major, beam 0 the
// starboard-most. Packed little-endian.
#pragma once
#include "core/shading/physics.hpp" // sound_speed_m_s
#include "core/display/polar_image.hpp"
#include "core/scene/scene.hpp"
#include "core/dataset/trajectory.hpp"
#include "core/io/byte_mapping.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace sonarsim {

/// Range geometry of an ARIS frame. ARIS stores the sample period and the start delay as whole
/// microseconds, so the sound speed written is the one that makes SamplePeriod exact for the bins
/// (about the water's, which sets only the rounding); samples sit at the bin centres.
struct ArisTiming {
    std::uint32_t sample_period_us = 0, sample_start_delay_us = 0;
    float sound_speed_m_s = 0;
    double window_start_m = 0, window_length_m = 0; ///< first sample's range, samples x sample length
};
ArisTiming aris_timing(const SonarParams& sonar, double water_sound_speed_m_s);

/// Throws the InputError write_aris would (naming the scene key) unless the scene can be an ARIS file: a
/// mode of its beam count (of the system an ARIS preset fixes) within 25 % of its frequency.
void check_aris(const SceneDesc& scene, const std::string& origin);

/// Writes every frame of `trajectory` as one .aris file (atomically: a temporary, then a rename), each
/// sample the byte of its image level (the frame's .npy: the sensor's output, TVG and gain included; with
/// the ideal sensor, L_EN) under `mapping`, whose levels of bytes 0 and 255 go into every frame header's
/// UserValue1 and UserValue2 [dB]. Pose and time go into the frame headers (SonarX/Y/Z,
/// SonarPan/Tilt/Roll = yaw/pitch/roll, FrameTime = t). Returns what the mapping clipped. Throws
/// InputError(origin, "sonar.beams", ...) unless the scene has 48, 64, 96 or 128 beams.
ExportReport write_aris(const std::string& path, const SceneDesc& scene, const Trajectory& trajectory,
                        const FrameImageSource& image, const ByteMapping& mapping, const std::string& origin);

} // namespace sonarsim

// ROS 2 marine_acoustic_msgs/msg/ProjectedSonarImage in CDR, and a bag of them in MCAP (SENSORS.md §3.2):
// range-major data, beam directions (0, -sin az, cos az) with az positive to port, ranges at the bin
// centres, ping_info with the frequency, sound speed and beam widths.
#pragma once
#include "core/io/aris.hpp"
#include "core/io/output.hpp"

#include <string>

namespace sonarsim {

enum class SonarDataType { Uint8, Float32 };

/// The message's .msg definition with its dependencies (MCAP schema encoding `ros2msg`).
const std::string& projected_sonar_image_schema();

/// One ProjectedSonarImage of `image` (L_EN dB) in CDR (little-endian, with its encapsulation header).
/// Uint8 data holds aris_byte(L_EN - display.lo_db); Float32 data holds L_EN [dB] (-inf where nothing
/// echoes).
Bytes encode_projected_sonar_image(const SceneDesc& scene, const PolarImage& image, double t_s,
                                   const std::string& frame_id, SonarDataType type);

/// Writes every frame of `trajectory` as a ROS 2 bag in MCAP (profile ros2, topic /sonarsim/image, frame
/// id "sonar", log time = t), atomically.
void write_sonar_mcap(const std::string& path, const SceneDesc& scene, const Trajectory& trajectory,
                      const FrameImageSource& image, SonarDataType type);

} // namespace sonarsim

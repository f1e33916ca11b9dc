// ROS 2 marine_acoustic_msgs/msg/ProjectedSonarImage in CDR, and a bag of them in MCAP (SENSORS.md §3.2):
// range-major data, beam directions (0, -sin az, cos az) with az positive to port, ranges at the bin
// centres, ping_info with the frequency, sound speed and beam widths.
#pragma once
#include "core/io/aris.hpp"
#include "core/io/output.hpp"

#include <cstdint>
#include <map>
#include <string>

namespace sonarsim {

enum class SonarDataType { Uint8, Float32 };

/// The message's .msg definition with its dependencies (MCAP schema encoding `ros2msg`).
const std::string& projected_sonar_image_schema();

/// One dependency of a ros2msg schema: the separator line, "MSG: NAME" and its definition; NAME one of
/// std_msgs/Header, builtin_interfaces/Time, marine_acoustic_msgs/PingInfo, geometry_msgs/Vector3,
/// marine_acoustic_msgs/SonarImageData.
std::string ros2msg_dependency(const std::string& name);

/// A sonar channel's MCAP metadata: offered_qos_profiles, and for uint8 data the image levels of bytes 0 and
/// 255 (byte_lo_db, byte_hi_db).
std::map<std::string, std::string> sonar_channel_metadata(SonarDataType type, const ByteMapping& mapping);

/// A time since 1970 in whole seconds and nanoseconds.
struct UnixTime {
    long long s = 0;
    std::uint32_t ns = 0;
};
/// start_s + t_s (start_s: UNIX seconds, at 0 or later; t_s >= 0), to the nanosecond.
UnixTime unix_time(double start_s, double t_s);

/// One ProjectedSonarImage of `image` (the image level dB, as the frame's .npy) in CDR (little-endian, with
/// its encapsulation header): header.stamp scene.exports.start_time_s + t_s, as the ARIS file's FrameTime;
/// rx_beamwidths each beam's -3 dB width (receive_beamwidth_rad). Uint8 data holds level_byte(L, mapping),
/// counted into `count`; Float32 data holds L [dB] (-inf where nothing echoes).
Bytes encode_projected_sonar_image(const SceneDesc& scene, const PolarImage& image, double t_s,
                                   const std::string& frame_id, SonarDataType type,
                                   const ByteMapping& mapping, ClipCount& count);

/// Writes every frame of `trajectory` as a ROS 2 bag in MCAP (profile ros2, topic /sonarsim/image, frame
/// id "sonar", log time = header.stamp = scene.exports.start_time_s + t, in ns), atomically. Uint8 data under
/// `mapping`, whose levels of bytes 0 and 255 the channel's metadata holds (byte_lo_db, byte_hi_db). Returns
/// what the mapping clipped (nothing for Float32).
ExportReport write_sonar_mcap(const std::string& path, const SceneDesc& scene, const Trajectory& trajectory,
                              const FrameImageSource& image, SonarDataType type, const ByteMapping& mapping);

} // namespace sonarsim

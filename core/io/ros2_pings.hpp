// A side-scan's or scanning sonar's pings as ROS 2 marine_acoustic_msgs/msg/RawSonarImage in CDR, and a
// bag of them in MCAP: one message per ping, one "beam" per channel (a side-scan's port and starboard, a
// scan's head), the samples of each beam in range order (beam-major data).
#pragma once
#include "core/io/ros2_sonar.hpp"
#include "core/kinds/ping_series.hpp"

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace sonarsim {

/// RawSonarImage's .msg definition with its dependencies (MCAP schema encoding `ros2msg`).
const std::string& raw_sonar_image_schema();

/// One ping: `levels` its channels' samples (channel-major, as PingSeries::profile), `ping` when and where
/// it was heard. header.stamp = scene.exports.start_time_s + t_s (the transmit); ping_info frequency, sound
/// speed, tx_beamwidths each channel's across-track width (sonar.elevation_fov_deg), rx_beamwidths its
/// along-track -3 dB width; sample_rate c / (2 dr) [Hz] for bins dr apart; samples_per_beam the bins;
/// sample0 the first bin's sample number since the transmit, round(range_min_m / dr); tx_delays and
/// tx_angles 0; rx_angles a side-scan's +pi/2 (port) and -pi/2 (starboard) about the track, a scan's head
/// angle [rad, toward port]; data uint8 (level_byte, counted into `count`) or float32 dB.
Bytes encode_raw_sonar_image(const SceneDesc& scene, const float* levels, const Ping& ping, double t_s,
                             const std::string& frame_id, SonarDataType type, const ByteMapping& mapping,
                             ClipCount& count);

/// One image of a dataset of pings: its scene (the frame's pose) and time on the dataset's clock, and its
/// levels as the frame's .npy holds them (pings x channels x bins).
struct PingFrame {
    SceneDesc scene;
    double t_s = 0;
    std::vector<float> level_db;
};
using PingFrameSource = std::function<PingFrame(std::size_t k)>;

/// Writes every ping of `frames` frames as a ROS 2 bag in MCAP (profile ros2, topic /sonarsim/pings, frame
/// id "sonar", log time = header.stamp = start + the frame's t + the ping's time), atomically. The report
/// counts what the mapping clipped per frame (every ping of it).
ExportReport write_ping_mcap(const std::string& path, std::size_t frames, const PingFrameSource& frame,
                             SonarDataType type, const ByteMapping& mapping);

} // namespace sonarsim

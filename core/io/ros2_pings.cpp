#include "core/io/ros2_pings.hpp"

#include "core/base/le_bytes.hpp"
#include "core/grid/sensor_patterns.hpp"
#include "core/io/cdr.hpp"
#include "core/io/mcap.hpp"
#include "core/kinds/pings.hpp"
#include "core/shading/physics.hpp"

#include <cmath>

namespace sonarsim {

const std::string& raw_sonar_image_schema() {
    static const std::string text = "std_msgs/Header header\n"
                                    "PingInfo ping_info\n"
                                    "float32 sample_rate\n"
                                    "uint32 samples_per_beam\n"
                                    "uint32 sample0\n"
                                    "float32[] tx_delays\n"
                                    "float32[] tx_angles\n"
                                    "float32[] rx_angles\n"
                                    "SonarImageData image\n" +
                                    ros2msg_dependency("std_msgs/Header") +
                                    ros2msg_dependency("builtin_interfaces/Time") +
                                    ros2msg_dependency("marine_acoustic_msgs/PingInfo") +
                                    ros2msg_dependency("marine_acoustic_msgs/SonarImageData");
    return text;
}

Bytes encode_raw_sonar_image(const SceneDesc& s, const float* levels, const Ping& ping, double t_s,
                             const std::string& frame_id, SonarDataType type, const ByteMapping& mapping,
                             ClipCount& count) {
    const SceneDesc beam = beam_scene(s);
    const auto grid = sonar_grid(beam.sonar);
    const auto channels = size_t(channel_count(s.sonar.kind)), bins = size_t(grid->bins);
    const double c = sound_speed_m_s(s.water.temperature_c, s.water.depth_m), dr = grid->bin_m;

    Cdr m;
    const UnixTime stamp = unix_time(s.exports.start_time_s, t_s);
    m.put<std::int32_t>(std::int32_t(stamp.s)); // header.stamp: the transmit
    m.put<std::uint32_t>(stamp.ns);
    m.put_string(frame_id);
    m.put<float>(float(s.sonar.frequency_khz * 1e3)); // ping_info
    m.put<float>(float(c));
    m.put_sequence(std::vector<float>(channels, float(s.sonar.elevation_fov_deg * kPi / 180)));
    m.put_sequence(std::vector<float>(channels, float(receive_beamwidth_rad(beam, *grid, 0))));
    m.put<float>(float(c / (2 * dr)));                                        // sample_rate [Hz]
    m.put<std::uint32_t>(std::uint32_t(bins));                                // samples_per_beam
    m.put<std::uint32_t>(std::uint32_t(std::lround(grid->range_min_m / dr))); // sample0
    m.put_sequence(std::vector<float>(channels, 0.0f));                       // tx_delays
    m.put_sequence(std::vector<float>(channels, 0.0f));                       // tx_angles
    std::vector<float> rx(channels);
    for (size_t ch = 0; ch < channels; ++ch)
        rx[ch] = s.sonar.kind == SonarKind::Sidescan ? float(ch == 0 ? kPi / 2 : -kPi / 2)
                                                     : float(ping.head_deg * kPi / 180);
    m.put_sequence(rx);                                         // rx_angles
    m.put<std::uint8_t>(0);                                     // image.is_bigendian
    m.put<std::uint32_t>(type == SonarDataType::Uint8 ? 0 : 8); // dtype
    m.put<std::uint32_t>(std::uint32_t(channels));              // beam_count
    Bytes data;
    if (type == SonarDataType::Uint8) {
        PolarImage one; // the ping's samples in their own order: beam-major, as the message wants
        one.bins = int(channels), one.beams = int(bins);
        one.level_db.assign(levels, levels + channels * bins);
        data = image_bytes(one, mapping, count);
    } else {
        le::append_bytes(data, levels, channels * bins * sizeof(float));
    }
    m.put_octets(data);
    return m.take();
}

ExportReport write_ping_mcap(const std::string& path, std::size_t frames, const PingFrameSource& frame,
                             SonarDataType type, const ByteMapping& mapping) {
    McapWriter w(path, "ros2", "sonarsim");
    const auto schema =
        w.add_schema("marine_acoustic_msgs/msg/RawSonarImage", "ros2msg", raw_sonar_image_schema());
    const auto channel =
        w.add_channel(schema, "/sonarsim/pings", "cdr", sonar_channel_metadata(type, mapping));
    ExportReport report;
    report.mapping = mapping;
    std::uint32_t sequence = 0;
    for (size_t k = 0; k < frames; ++k) {
        const PingFrame f = frame(k);
        const std::vector<Ping> schedule = ping_schedule(f.scene);
        const size_t per_ping = size_t(channel_count(f.scene.sonar.kind)) * size_t(f.scene.sonar.range_bins);
        ClipCount count;
        for (size_t p = 0; p < schedule.size(); ++p) {
            const double t = std::max(0.0, f.t_s) + schedule[p].time_s;
            const UnixTime at = unix_time(f.scene.exports.start_time_s, t);
            w.add_message(channel, sequence++, std::uint64_t(at.s) * 1000000000ULL + at.ns,
                          encode_raw_sonar_image(f.scene, f.level_db.data() + p * per_ping, schedule[p], t,
                                                 "sonar", type, mapping, count));
        }
        report.frames.push_back(count);
        report.total += count;
    }
    w.finish();
    return report;
}

} // namespace sonarsim

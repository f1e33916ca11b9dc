#include "core/io/ros2_sonar.hpp"

#include "core/grid/sensor_patterns.hpp"

#include "core/base/le_bytes.hpp"
#include "core/io/cdr.hpp"
#include "core/io/mcap.hpp"
#include "core/data/pose.hpp"
#include "core/grid/sonar_grid.hpp"

#include <cmath>
#include <cstdio>
#include <map>

namespace sonarsim {

std::string ros2msg_dependency(const std::string& name) {
    static const std::string sep = "\n" + std::string(80, '=') + "\n";
    static const std::map<std::string, std::string> defs = {
        {"std_msgs/Header", "builtin_interfaces/Time stamp\nstring frame_id\n"},
        {"builtin_interfaces/Time", "int32 sec\nuint32 nanosec\n"},
        {"marine_acoustic_msgs/PingInfo",
         "float32 frequency\nfloat32 sound_speed\nfloat32[] tx_beamwidths\nfloat32[] rx_beamwidths\n"},
        {"geometry_msgs/Vector3", "float64 x\nfloat64 y\nfloat64 z\n"},
        {"marine_acoustic_msgs/SonarImageData",
         "bool is_bigendian\n"
         "uint32 DTYPE_UINT8=0\nuint32 DTYPE_INT8=1\nuint32 DTYPE_UINT16=2\nuint32 DTYPE_INT16=3\n"
         "uint32 DTYPE_UINT32=4\nuint32 DTYPE_INT32=5\nuint32 DTYPE_UINT64=6\nuint32 DTYPE_INT64=7\n"
         "uint32 DTYPE_FLOAT32=8\nuint32 DTYPE_FLOAT64=9\n"
         "uint32 dtype\nuint32 beam_count\nuint8[] data\n"}};
    return sep + "MSG: " + name + "\n" + defs.at(name);
}

const std::string& projected_sonar_image_schema() {
    static const std::string text =
        "std_msgs/Header header\n"
        "PingInfo ping_info\n"
        "geometry_msgs/Vector3[] beam_directions\n"
        "float32[] ranges\n"
        "SonarImageData image\n" +
        ros2msg_dependency("std_msgs/Header") + ros2msg_dependency("builtin_interfaces/Time") +
        ros2msg_dependency("marine_acoustic_msgs/PingInfo") + ros2msg_dependency("geometry_msgs/Vector3") +
        ros2msg_dependency("marine_acoustic_msgs/SonarImageData");
    return text;
}

std::map<std::string, std::string> sonar_channel_metadata(SonarDataType type, const ByteMapping& mapping) {
    std::map<std::string, std::string> metadata{{"offered_qos_profiles", ""}};
    if (type == SonarDataType::Uint8) {
        char lo[32], hi[32];
        std::snprintf(lo, sizeof lo, "%.9g", mapping.lo_db);
        std::snprintf(hi, sizeof hi, "%.9g", mapping.hi_db);
        metadata["byte_lo_db"] = lo; // the image levels of bytes 0 and 255
        metadata["byte_hi_db"] = hi;
    }
    return metadata;
}

UnixTime unix_time(double start_s, double t_s) {
    // Whole seconds of the start apart from its fraction, so that nanoseconds survive at 1.7e9 s.
    const double whole = std::floor(std::max(0.0, start_s)), rel = std::max(0.0, start_s) - whole + t_s;
    const double rel_whole = std::floor(rel);
    auto ns = std::llround((rel - rel_whole) * 1e9);
    auto sec = (long long)(whole) + (long long)(rel_whole);
    if (ns >= 1000000000LL) ++sec, ns -= 1000000000LL;
    return {sec, std::uint32_t(ns)};
}

Bytes encode_projected_sonar_image(const SceneDesc& s, const PolarImage& img, double t_s,
                                   const std::string& frame_id, SonarDataType type,
                                   const ByteMapping& mapping, ClipCount& count) {
    Cdr c;
    const UnixTime stamp = unix_time(s.exports.start_time_s, t_s);
    c.put<std::int32_t>(std::int32_t(stamp.s)); // header.stamp: the dataset's start plus t
    c.put<std::uint32_t>(stamp.ns);
    c.put_string(frame_id);

    const auto beams = size_t(img.beams);
    c.put<float>(float(s.sonar.frequency_khz * 1e3)); // ping_info
    c.put<float>(float(sound_speed_m_s(s.water.temperature_c, s.water.depth_m)));
    c.put_sequence(std::vector<float>(beams, float(s.sonar.elevation_fov_deg * kPi / 180)));
    const auto grid = sonar_grid(s.sonar);
    std::vector<float> widths(beams); // rx_beamwidths: each beam's -3 dB width, as the message defines it
    for (size_t i = 0; i < beams; ++i) widths[i] = float(receive_beamwidth_rad(s, *grid, int(i)));
    c.put_sequence(widths);

    c.put<std::uint32_t>(std::uint32_t(beams)); // beam_directions
    for (double az_deg : grid->beam_azimuths_deg()) {
        c.put<double>(0.0);
        c.put<double>(-std::sin(az_deg * kPi / 180));
        c.put<double>(std::cos(az_deg * kPi / 180));
    }
    const std::vector<double> edges = grid->bin_edges_m();
    std::vector<float> ranges;
    for (size_t i = 0; i + 1 < edges.size(); ++i) ranges.push_back(float(0.5 * (edges[i] + edges[i + 1])));
    c.put_sequence(ranges);

    c.put<std::uint8_t>(0); // image.is_bigendian
    c.put<std::uint32_t>(type == SonarDataType::Uint8 ? 0 : 8);
    c.put<std::uint32_t>(std::uint32_t(beams));
    Bytes data;
    if (type == SonarDataType::Uint8) {
        data = image_bytes(img, mapping, count);
    } else {
        le::append_bytes(data, img.level_db.data(), img.level_db.size() * sizeof(float));
    }
    c.put_octets(data); // range-major: the image's rows are range bins
    return c.take();
}

ExportReport write_sonar_mcap(const std::string& path, const SceneDesc& s, const Trajectory& trajectory,
                              const FrameImageSource& image, SonarDataType type, const ByteMapping& mapping) {
    McapWriter w(path, "ros2", "sonarsim");
    const auto schema = w.add_schema("marine_acoustic_msgs/msg/ProjectedSonarImage", "ros2msg",
                                     projected_sonar_image_schema());
    const auto channel =
        w.add_channel(schema, "/sonarsim/image", "cdr", sonar_channel_metadata(type, mapping));
    ExportReport report;
    report.mapping = mapping;
    for (size_t k = 0; k < trajectory.size(); ++k) {
        const double t = std::max(0.0, trajectory[k].t_s);
        const UnixTime at = unix_time(s.exports.start_time_s, t); // log time on the ARIS file's clock
        ClipCount count;
        w.add_message(channel, std::uint32_t(k), std::uint64_t(at.s) * 1000000000ULL + at.ns,
                      encode_projected_sonar_image(s, image(k), t, "sonar", type, mapping, count));
        report.frames.push_back(count);
        report.total += count;
    }
    w.finish();
    return report;
}

} // namespace sonarsim

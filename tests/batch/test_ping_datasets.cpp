// Datasets of side-scan and scanning sonars: each frame the kind's image from the frame's pose (its files,
// its ground truth, the index), and the dataset as a ROS 2 bag of marine_acoustic_msgs/RawSonarImage read
// back by the tests' own MCAP and CDR reader, field by field against the frames' files and closed forms.
#include "mcap_read.hpp"
#include "support.hpp"

#include "core/base/errors.hpp"
#include "core/dataset/batch.hpp"
#include "core/dataset/export.hpp"
#include "core/io/output.hpp"
#include "core/kinds/ping_series.hpp"
#include "core/scene/params.hpp"
#include "core/shading/physics.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <string>

using namespace sonarsim;
using namespace sonarsim::test;

namespace {

/// A side-scan 5 m above a flat floor with a box on the starboard side, 3 pings a frame.
SceneDesc sidescan_dataset_scene() {
    SceneDesc s;
    apply_setting(s, "sonar.kind", "sidescan", "test");
    s.sonar.pose = {{0, 0, 5}, {0, 0, 0}};
    s.sonar.frequency_khz = 400;
    s.sonar.azimuth_fov_deg = 1.0, s.sonar.elevation_fov_deg = 80;
    s.sidescan.depression_deg = 40, s.sidescan.pings = 3;
    s.sonar.range_min_m = 0.5, s.sonar.range_max_m = 20, s.sonar.range_bins = 200;
    s.sonar.source_level_db = 210, s.sonar.noise_level_db = 40;
    s.seafloor = Seafloor{};
    s.seafloor->material.nu_db = -30;
    s.sonar.motion_from_trajectory = true; // a frame's pings move along the trajectory
    ObjectDesc o;
    o.box_m = {2, 2, 1}, o.position_m = {0.5, -8, 0.5};
    s.objects.push_back(o);
    validate_scene(s, "test");
    return s;
}

/// A scanning sonar 1 m above the floor, 11 steps from 0 to 36 deg.
SceneDesc scanning_dataset_scene() {
    SceneDesc s;
    apply_setting(s, "sonar.kind", "scanning", "test");
    s.sonar.pose = {{0, 0, 1}, {0, 0, 0}};
    s.sonar.range_min_m = 0.75, s.sonar.range_max_m = 10, s.sonar.range_bins = 100;
    s.scanning.sector_start_deg = 0, s.scanning.sector_end_deg = 36, s.scanning.step_deg = 3.6;
    s.seafloor = Seafloor{};
    validate_scene(s, "test");
    return s;
}

/// The shape in an .npy file's header, e.g. "(3, 2, 200, 3)".
std::string npy_shape(const std::string& path) {
    const auto b = file_bytes(path);
    const std::string header(b.begin() + 10, b.begin() + 10 + long(size_t(b[8]) | size_t(b[9]) << 8));
    const size_t at = header.find("'shape': ");
    return header.substr(at + 9, header.find(')', at) - at - 8);
}

/// The RawSonarImage fields the tests check, read in the message's field order from its CDR bytes.
struct RawSonarImage {
    std::uint64_t stamp_ns = 0;
    std::string frame_id;
    float frequency = 0, sound_speed = 0;
    std::vector<float> tx_beamwidths, rx_beamwidths;
    float sample_rate = 0;
    std::uint32_t samples_per_beam = 0, sample0 = 0;
    std::vector<float> tx_delays, tx_angles, rx_angles;
    std::uint32_t dtype = 0, beam_count = 0;
    std::vector<std::uint8_t> data;
};

RawSonarImage decode_raw_sonar_image(const std::vector<std::uint8_t>& msg) {
    REQUIRE(msg.size() > 4);
    REQUIRE(msg[1] == 0x01); // CDR little-endian encapsulation
    Reader c{msg, 4, 4};
    RawSonarImage m;
    const auto sec = c.get<std::int32_t>(true);
    m.stamp_ns = std::uint64_t(sec) * 1000000000ULL + c.get<std::uint32_t>(true);
    m.frame_id = c.str(true);
    auto floats = [&] {
        std::vector<float> v(c.get<std::uint32_t>(true));
        for (float& x : v) x = c.get<float>(true);
        return v;
    };
    m.frequency = c.get<float>(true), m.sound_speed = c.get<float>(true);
    m.tx_beamwidths = floats(), m.rx_beamwidths = floats();
    m.sample_rate = c.get<float>(true);
    m.samples_per_beam = c.get<std::uint32_t>(true), m.sample0 = c.get<std::uint32_t>(true);
    m.tx_delays = floats(), m.tx_angles = floats(), m.rx_angles = floats();
    CHECK(c.get<std::uint8_t>() == 0); // image.is_bigendian
    m.dtype = c.get<std::uint32_t>(true), m.beam_count = c.get<std::uint32_t>(true);
    const auto n = c.get<std::uint32_t>(true);
    REQUIRE(c.p + n == msg.size());
    m.data.assign(msg.begin() + long(c.p), msg.end());
    return m;
}

} // namespace

TEST_CASE("a side-scan dataset: each frame the waterfall from its pose, its XTF and ground truth, the index",
          "[batch][kinds]") {
    const std::string dir = batch_out("kinds_sidescan");
    const SceneDesc scene = sidescan_dataset_scene();
    const Trajectory t = line_trajectory("0,0,5,2,0,5,3", {0, 0, 0}, 4, "test");
    prepare_dataset(dir, scene, t);
    BatchOptions o;
    o.ground_truth = true;
    const BatchSummary r = run_batch(dir, o);
    CHECK(r.rendered == 3);
    CHECK(r.indexed == 3);
    SceneDesc base;
    Trajectory stored;
    load_dataset(dir, base, stored);
    for (size_t k = 0; k < 3; ++k) {
        CHECK(frame_complete(dir, k, base));
        CHECK(std::filesystem::is_regular_file(frame_prefix(dir, k) + ".xtf"));
        // The frame is the waterfall a render of the frame's scene makes, byte for byte.
        const PingSeries p = render_pings(frame_scene(base, stored, k));
        const auto b = file_bytes(frame_prefix(dir, k) + ".npy");
        CHECK(decode_npy_values(b, "npy", p.level_db.size()) == p.level_db);
        CHECK(npy_shape(frame_prefix(dir, k) + ".npy") == "(3, 2, 200)");
        CHECK(npy_shape(frame_prefix(dir, k) + "_gt_point_m.npy") == "(3, 2, 200, 3)");
        CHECK(npy_shape(frame_prefix(dir, k) + "_gt_object_id.npy") == "(3, 2, 200)");
        // Each ping is heard from the trajectory's pose at its time: frame k's at t_k, then 4 m/s along x.
        const double v_m_s =
            (stored[2].pose.position_m[0] - stored[0].pose.position_m[0]) / (stored[2].t_s - stored[0].t_s);
        CHECK(v_m_s == Approx(4));
        for (int i = 0; i < 3; ++i)
            CHECK(p.schedule[size_t(i)].vehicle.position_m[0] ==
                  Approx(stored[k].pose.position_m[0] + v_m_s * p.schedule[size_t(i)].time_s));
    }
    const auto index_bytes = file_bytes(dir + "/index.csv");
    const std::string index(index_bytes.begin(), index_bytes.end());
    CHECK(index.find("frames/000002.xtf") != std::string::npos);
    CHECK(index.find("frames/000001_gt_incidence_deg.npy") != std::string::npos);
    // A container that holds no pings says which do (dataset_containers: one row each).
    CHECK_THROWS_AS(
        export_dataset(dir, dir + "/out.aris", dataset_container("--aris"), false, base.exports, "--aris"),
        InputError);
    CHECK_THROWS_WITH(
        export_dataset(dir, dir + "/out.aris", dataset_container("--aris"), false, base.exports, "--aris"),
        Catch::Contains("allowed: --mcap (each frame also has its own .xtf)"));
    CHECK(containers_for(SonarKind::Imaging) == "--aris, --mcap");
    CHECK_FALSE(std::filesystem::exists(dir + "/out.aris"));
    CHECK_THROWS_AS(dataset_images(dir, 3, "--aris"), InputError);
}

TEST_CASE("a side-scan and a scan as ROS 2 bags of RawSonarImage read back field by field", "[batch][mcap]") {
    for (const bool side : {true, false}) {
        const std::string dir = batch_out(side ? "kinds_mcap_sidescan" : "kinds_mcap_scan");
        const SceneDesc scene = side ? sidescan_dataset_scene() : scanning_dataset_scene();
        const Trajectory t = side ? line_trajectory("0,0,5,2,0,5,3", {0, 0, 0}, 4, "test")
                                  : line_trajectory("0,0,1,0,0,1,1", {0, 0, 0}, 1, "test");
        prepare_dataset(dir, scene, t);
        run_batch(dir, {});
        SceneDesc base;
        Trajectory stored;
        load_dataset(dir, base, stored);
        const double c = sound_speed_m_s(base.water.temperature_c, base.water.depth_m);
        const double dr = (base.sonar.range_max_m - base.sonar.range_min_m) / base.sonar.range_bins;
        const int channels = side ? 2 : 1, bins = base.sonar.range_bins;
        ExportParams exports = base.exports;
        exports.start_time_s = 1700000000.5;
        for (const bool float32 : {true, false}) {
            const std::string path = dir + "/out.mcap";
            const ExportReport report =
                export_dataset(dir, path, dataset_container("--mcap"), float32, exports, "--mcap");
            const McapContents m = mcap_contents(file_bytes(path));
            CHECK(m.profile == "ros2");
            REQUIRE(m.channel_schema.count(0));
            CHECK(m.schema_name.at(m.channel_schema.at(0)) == "marine_acoustic_msgs/msg/RawSonarImage");
            CHECK(m.channel_topic.at(0) == "/sonarsim/pings");
            size_t i = 0;
            for (size_t k = 0; k < stored.size(); ++k) {
                const PingSeries p = render_pings(frame_scene(base, stored, k));
                for (int ping = 0; ping < p.pings; ++ping, ++i) {
                    REQUIRE(i < m.messages.size());
                    const RawSonarImage r = decode_raw_sonar_image(m.messages[i].data);
                    // The transmit on the dataset's clock: start + t_k + the ping's time, to the nanosecond.
                    const double rel_s = 0.5 + stored[k].t_s + p.schedule[size_t(ping)].time_s;
                    const auto want_ns =
                        1700000000ULL * 1000000000ULL + std::uint64_t(std::llround(rel_s * 1e9));
                    CHECK(std::llabs((long long)(r.stamp_ns) - (long long)(want_ns)) <= 1);
                    CHECK(m.messages[i].log_time_ns == r.stamp_ns);
                    CHECK(r.frame_id == "sonar");
                    CHECK(r.frequency == Approx(base.sonar.frequency_khz * 1e3));
                    CHECK(r.sound_speed == Approx(c));
                    CHECK(r.sample_rate == Approx(c / (2 * dr))); // one sample per bin of two-way time
                    CHECK(r.samples_per_beam == std::uint32_t(bins));
                    CHECK(r.sample0 == std::uint32_t(std::lround(base.sonar.range_min_m / dr)));
                    REQUIRE(r.beam_count == std::uint32_t(channels));
                    REQUIRE(r.rx_angles.size() == size_t(channels));
                    CHECK(r.tx_beamwidths.size() == size_t(channels));
                    CHECK(r.rx_beamwidths.size() == size_t(channels));
                    CHECK(r.tx_delays == std::vector<float>(size_t(channels), 0.0f));
                    if (side) {
                        CHECK(r.rx_angles[0] == Approx(kPi / 2)); // port
                        CHECK(r.rx_angles[1] == Approx(-kPi / 2));
                    } else {
                        CHECK(r.rx_angles[0] == Approx(p.schedule[size_t(ping)].head_deg * kPi / 180));
                    }
                    // Beam-major samples, each channel's in range order, as the frame's .npy holds them.
                    const float* levels = p.profile(ping, 0);
                    const size_t n = size_t(channels) * size_t(bins);
                    if (float32) {
                        CHECK(r.dtype == 8);
                        REQUIRE(r.data.size() == 4 * n);
                        for (size_t j = 0; j < n; ++j) {
                            const float v = at<float>(r.data, 4 * j);
                            CHECK((v == levels[j] || (std::isinf(v) && std::isinf(levels[j]))));
                        }
                    } else {
                        CHECK(r.dtype == 0);
                        REQUIRE(r.data.size() == n);
                        for (size_t j = 0; j < n; ++j)
                            CHECK(r.data[j] == level_byte(levels[j], report.mapping));
                    }
                }
            }
            CHECK(i == m.messages.size());
        }
    }
}

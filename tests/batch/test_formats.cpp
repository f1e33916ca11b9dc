// ARIS and MCAP files read back by readers written here from the specifications (SENSORS.md §3.1 and
// Appendix A; the MCAP specification and OMG CDR), not with the writers' code; PNG files likewise (chunks
// and CRCs here, pixels decoded by stb_image).
#include "mcap_read.hpp"
#include "support.hpp"

#include "core/io/aris.hpp"
#include "core/dataset/batch.hpp"
#include "core/base/errors.hpp"
#include "core/grid/beam_tables.hpp"
#include "core/io/output.hpp"
#include "core/data/pose.hpp"
#include "core/io/ros2_sonar.hpp"
#include "core/shading/physics.hpp"

#include "core/grid/sonar_grid.hpp"
#include <catch2/catch.hpp>
#include <cstdlib>
#include <random>
#include <stb/stb_image.h>
#include <cmath>
#include <cstring>
#include <map>

using namespace sonarsim;
using namespace sonarsim::test;

namespace {

SceneDesc with_gain(SceneDesc s, double gain_db) {
    s.sensor.gain_db = gain_db;
    return s;
}

/// The mapping these tests read the files with: bytes 0 ... 255 = image levels 0 ... 80 dB.
const ByteMapping kZeroTo80{0, 80, false};

/// A dataset of 3 frames of the small ARIS scene (48 beams, 256 bins) along a line.
struct Dataset {
    std::string dir;
    SceneDesc scene = with_gain(small_aris_scene(), -80); // L_EN 80 ... 130 dB into the bytes' 0 ... 80 dB
    Trajectory trajectory = line_trajectory("0.3,2.4,0.9,0.4,2.3,0.9,3", {-1, 30, -39}, 6.5, "test");
    std::vector<PolarImage> images;
    explicit Dataset(const std::string& name) {
        dir = batch_out(name);
        prepare_dataset(dir, scene, trajectory);
        run_batch(dir, {});
        for (size_t k = 0; k < trajectory.size(); ++k) {
            Bytes b = file_bytes(frame_prefix(dir, k) + ".npy");
            images.push_back(decode_npy(b, "npy"));
        }
    }
};

/// One directory per test case: ctest runs them as parallel processes.
const Dataset& dataset(const std::string& name) {
    static const Dataset d(name);
    return d;
}

/// The level a byte stands for in the test's own reading of the documented mapping: byte 80/255 dB above
/// `lo_db` (0: the image level itself).
double byte_level(std::uint8_t b, double lo_db) {
    return b * 80.0 / 255.0 + lo_db;
}

/// Checks a byte against the L_EN level it was written from: within half a quantisation step, and
/// clamped at the ends.
void check_byte(std::uint8_t byte, float level, double lo_db) {
    const double l = double(level);
    if (!std::isfinite(l) || l <= lo_db)
        CHECK(byte == 0);
    else if (l >= lo_db + 80)
        CHECK(byte == 255);
    else
        CHECK(std::abs(byte_level(byte, lo_db) - l) <= 0.5 * 80.0 / 255.0 + 1e-4);
}

std::uint32_t bitwise_crc32(const std::uint8_t* p, size_t n) {
    std::uint32_t c = 0xffffffffu;
    for (size_t i = 0; i < n; ++i) {
        c ^= p[i];
        for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
    }
    return ~c;
}

} // namespace

TEST_CASE("an ARIS file read from its specification gives back the frames", "[aris]") {
    const Dataset& d = dataset("formats_aris");
    const std::string path = d.dir + "/out.aris";
    write_aris(path, d.scene, d.trajectory, dataset_images(d.dir, 3, "--aris"), kZeroTo80, "--aris");
    const auto b = file_bytes(path);
    const size_t beams = at<std::uint32_t>(b, 1024 + 436) == 1 ? 48 : 0; // PingMode 1: 48 beams
    REQUIRE(beams == 48);
    // The water's sound speed; SamplePeriod the whole us nearest 2 bin / c; as many samples as cover the
    // window; the first at the first bin's centre, to the whole us of SampleStartDelay.
    const double c_water = sound_speed_m_s(d.scene.water.temperature_c, d.scene.water.depth_m);
    const double bin = (d.scene.sonar.range_max_m - d.scene.sonar.range_min_m) / d.scene.sonar.range_bins;
    const double sp = std::round(2 * bin / c_water * 1e6);
    const size_t samples = at<std::uint32_t>(b, 1024 + 468);
    CHECK(samples ==
          size_t(std::round((d.scene.sonar.range_max_m - d.scene.sonar.range_min_m) / (sp * c_water / 2e6))));
    const size_t frame_bytes = 1024 + beams * samples;
    REQUIRE((b.size() - 1024) % frame_bytes == 0);
    REQUIRE((b.size() - 1024) / frame_bytes == 3); // frame count from the size, as readers should
    CHECK(at<std::uint32_t>(b, 0) == 0x05464444);
    CHECK(std::memcmp(b.data(), "DDF\x05", 4) == 0);
    CHECK(at<std::uint32_t>(b, 4) == 3);
    CHECK(at<std::uint32_t>(b, 16) == 48);
    CHECK(at<std::uint32_t>(b, 24) == samples);

    for (size_t k = 0; k < 3; ++k) {
        const size_t f = 1024 + k * frame_bytes;
        CHECK(at<std::uint32_t>(b, f + 0) == k);
        CHECK(at<std::uint32_t>(b, f + 12) == 0x05464444);
        CHECK(at<std::uint32_t>(b, f + 516) == 1); // reordered: sample-major
        CHECK(at<std::uint64_t>(b, f + 4) == std::uint64_t(std::llround(d.trajectory[k].t_s * 1e6)));
        CHECK(at<float>(b, f + 232) == Approx(d.trajectory[k].pose.position_m[0]));
        // Range of sample i: SampleStartDelay, SamplePeriod [us] and SoundSpeed [m/s].
        const double c = at<float>(b, f + 464);
        CHECK(c == Approx(c_water).epsilon(1e-6));
        CHECK(at<std::uint32_t>(b, f + 452) == std::uint32_t(sp));
        CHECK(at<std::uint32_t>(b, f + 476) ==
              std::uint32_t(std::round(2 * (d.scene.sonar.range_min_m + bin / 2) / c_water * 1e6)));
        const double start = at<std::uint32_t>(b, f + 476) * 1e-6 * c / 2;
        const double step = at<std::uint32_t>(b, f + 452) * 1e-6 * c / 2;
        CHECK(at<float>(b, f + 52) == Approx(start).epsilon(1e-6)); // WindowStart, WindowLength [m]
        CHECK(at<float>(b, f + 56) == Approx(step * double(samples)).epsilon(1e-6));
        // The device's grid is not our bins: the last sample lies well off the last bin's centre.
        CHECK(std::abs(start + double(samples - 1) * step - (d.scene.sonar.range_max_m - bin / 2)) > 0.005);
        const PolarImage& img = d.images[k];
        size_t lit = 0;
        for (size_t s = 0; s < samples; ++s)
            for (size_t beam = 0; beam < beams; ++beam) {
                const std::uint8_t byte = b[f + 1024 + s * beams + beam];
                // ARIS beam 0 is the starboard-most: the image's last column; sample s at its range.
                const double r = start + double(s) * step;
                check_byte(byte,
                           level_at_range(img, int(beams - 1 - beam), d.scene.sonar.range_min_m,
                                          d.scene.sonar.range_max_m, r),
                           0.0);
                lit += byte > 0;
            }
        CHECK(lit > 100); // the frame is not blank
    }
}

TEST_CASE("an MCAP bag read from its specification gives back the frames", "[mcap]") {
    const Dataset& d = dataset("formats_mcap");
    // On the ARIS file's clock: the dataset's start plus t, to the nanosecond.
    SceneDesc scene = d.scene;
    scene.exports.start_time_s = 1700000000.25;
    auto stamp_ns = [&](size_t k) {
        return 1700000000250000000ULL + std::uint64_t(std::llround(d.trajectory[k].t_s * 1e9));
    };
    for (const auto type : {SonarDataType::Uint8, SonarDataType::Float32}) {
        const std::string path = d.dir + "/out.mcap";
        write_sonar_mcap(path, scene, d.trajectory, dataset_images(d.dir, 3, "--mcap"), type, kZeroTo80);
        const auto b = file_bytes(path);
        const auto recs = mcap_records(b);
        REQUIRE(recs.front().op == 0x01);
        {
            Reader h{recs.front().content};
            CHECK(h.str() == "ros2");
        }
        REQUIRE(recs.back().op == 0x02);
        Reader footer{recs.back().content};
        const auto summary_start = footer.get<std::uint64_t>();
        std::map<std::uint16_t, std::string> schema_of_channel, schemas;
        std::vector<std::vector<std::uint8_t>> messages;
        bool data_end = false;
        size_t chunk_indexes = 0;
        for (const Record& r : recs) {
            Reader in{r.content};
            if (r.op == 0x0F) {
                data_end = true;
                CHECK(r.offset + 13 == summary_start);
            }
            if (data_end) {
                chunk_indexes += r.op == 0x08;
                continue; // the summary repeats the schema and channel
            }
            if (r.op == 0x03) {
                const auto id = in.get<std::uint16_t>();
                schemas[id] = in.str();
                CHECK(in.str() == "ros2msg");
                CHECK(in.str().find("SonarImageData image") != std::string::npos);
            } else if (r.op == 0x04) {
                in.get<std::uint16_t>();
                const auto schema = in.get<std::uint16_t>();
                in.str();
                CHECK(in.str() == "cdr");
                CHECK(in.get<std::uint32_t>() > 0); // metadata map: offered_qos_profiles
                schema_of_channel[0] = schemas.at(schema);
            } else if (r.op == 0x06) {
                in.get<std::uint64_t>(), in.get<std::uint64_t>();
                const auto size = in.get<std::uint64_t>();
                const auto crc = in.get<std::uint32_t>();
                CHECK(in.str().empty()); // uncompressed
                REQUIRE(in.get<std::uint64_t>() == size);
                CHECK(crc == bitwise_crc32(r.content.data() + in.p, size_t(size)));
                REQUIRE(r.content[in.p] == 0x05); // the chunk holds one Message record
                Reader m{r.content, in.p + 9};
                CHECK(m.get<std::uint16_t>() == 0);
                const auto seq = m.get<std::uint32_t>();
                CHECK(m.get<std::uint64_t>() == stamp_ns(seq)); // log time
                m.get<std::uint64_t>();
                messages.emplace_back(r.content.begin() + long(m.p), r.content.end());
            }
        }
        CHECK(schema_of_channel[0] == "marine_acoustic_msgs/msg/ProjectedSonarImage");
        CHECK(chunk_indexes == 3);
        REQUIRE(messages.size() == 3);

        const std::vector<double> az = sonar_grid(d.scene.sonar)->beam_azimuths_deg(),
                                  edges = sonar_grid(d.scene.sonar)->bin_edges_m();
        for (size_t k = 0; k < 3; ++k) {
            const auto& msg = messages[k];
            REQUIRE(msg[1] == 0x01); // CDR little-endian encapsulation
            Reader c{msg, 4, 4};
            const auto sec = c.get<std::int32_t>(true);
            const auto nsec = c.get<std::uint32_t>(true);
            CHECK(std::uint64_t(sec) * 1000000000ULL + nsec == stamp_ns(k));
            CHECK(c.str(true) == "sonar");
            CHECK(c.get<float>(true) == Approx(1.2e6));           // frequency [Hz]
            CHECK(c.get<float>(true) == Approx(1490).margin(20)); // sound speed
            const auto tx = c.get<std::uint32_t>(true);
            for (size_t i = 0; i < tx; ++i) CHECK(c.get<float>(true) == Approx(14 * kPi / 180));
            const auto rx = c.get<std::uint32_t>(true);
            // The ideal sensor's beams are hard-edged cells: their -3 dB width is their own width.
            for (size_t i = 0; i < rx; ++i) CHECK(c.get<float>(true) == Approx(32.0 / 48 * kPi / 180));
            const auto beams = c.get<std::uint32_t>(true);
            REQUIRE(beams == 48);
            for (size_t i = 0; i < beams; ++i) {
                const double x = c.get<double>(true), y = c.get<double>(true), z = c.get<double>(true);
                CHECK(x == 0);
                CHECK(y * y + z * z == Approx(1));
                CHECK(std::atan2(-y, z) * 180 / kPi == Approx(az[i])); // positive to port
            }
            const auto n_ranges = c.get<std::uint32_t>(true);
            REQUIRE(int(n_ranges) == d.scene.sonar.range_bins);
            for (size_t i = 0; i < n_ranges; ++i)
                CHECK(c.get<float>(true) == Approx(0.5 * (edges[i] + edges[i + 1])));
            CHECK(c.get<std::uint8_t>() == 0); // is_bigendian
            const auto dtype = c.get<std::uint32_t>(true);
            CHECK(c.get<std::uint32_t>(true) == 48);
            const auto n = c.get<std::uint32_t>(true);
            const PolarImage& img = d.images[k];
            if (type == SonarDataType::Uint8) {
                CHECK(dtype == 0);
                REQUIRE(n == n_ranges * 48);
                for (size_t r = 0; r < n_ranges; ++r) // range-major: all beams of bin 0, then of bin 1, ...
                    for (size_t beam = 0; beam < 48; ++beam)
                        check_byte(msg[c.p + r * 48 + beam], img.at(int(r), int(beam)), 0.0);
            } else {
                CHECK(dtype == 8);
                REQUIRE(n == n_ranges * 48 * 4);
                for (size_t i = 0; i < n_ranges * 48; i += 97) {
                    const float v = at<float>(msg, c.p + 4 * i);
                    CHECK((v == img.level_db[i] || (std::isinf(v) && std::isinf(img.level_db[i]))));
                }
            }
            CHECK(c.p + n == msg.size());
        }
    }
}

TEST_CASE("a ROS 2 sonar message carries each beam's bearing and width from its table",
          "[mcap][beam_table]") {
    // ARIS 1200 / 1800 LF: 48 beams, 0.43 deg wide at the fan's edges, 0.69 deg at its centre.
    SceneDesc s;
    apply_setting_text(s, "sonar.beams=48", "test");
    apply_setting_text(s, "sonar.azimuth_fov_deg=27.58", "test");
    apply_setting_text(s, "sonar.beam_table=aris1800_1200_48", "test");
    const BeamTable& t = *find_beam_table("aris1800_1200_48");
    PolarImage img;
    img.beams = 48, img.bins = s.sonar.range_bins;
    img.level_db.assign(size_t(img.beams) * size_t(img.bins), 30.0f);
    ClipCount count;
    const auto msg = encode_projected_sonar_image(s, img, 1.0, "sonar", SonarDataType::Float32,
                                                  ByteMapping{0, 80, false}, count);
    Reader c{msg, 4, 4};
    c.get<std::int32_t>(true), c.get<std::uint32_t>(true), c.str(true);
    c.get<float>(true), c.get<float>(true); // frequency, sound speed
    const auto tx = c.get<std::uint32_t>(true);
    for (size_t i = 0; i < tx; ++i) c.get<float>(true);
    REQUIRE(c.get<std::uint32_t>(true) == 48); // rx widths
    for (size_t i = 0; i < 48; ++i)
        CHECK(c.get<float>(true) ==
              Approx((t.port_edge_deg[i] - t.starboard_edge_deg[i]) * kPi / 180).epsilon(1e-6));
    REQUIRE(c.get<std::uint32_t>(true) == 48);
    for (size_t i = 0; i < 48; ++i) {
        c.get<double>(true);
        const double y = c.get<double>(true), z = c.get<double>(true);
        CHECK(std::atan2(-y, z) * 180 / kPi == Approx(t.centre_deg[i]).margin(1e-9)); // positive to port
    }
}

namespace {

std::uint32_t be32(const std::vector<std::uint8_t>& b, size_t at) {
    return std::uint32_t(b[at]) << 24 | std::uint32_t(b[at + 1]) << 16 | std::uint32_t(b[at + 2]) << 8 |
           b[at + 3];
}

Image8 random_image(int w, int h, int channels, std::uint32_t seed) {
    Image8 img{w, h, channels, {}};
    img.pixels.resize(size_t(w) * size_t(h) * size_t(channels));
    std::mt19937 rng(seed);
    // Runs of one value with noise between them, like a fan image's background and its echoes.
    for (size_t i = 0; i < img.pixels.size(); ++i)
        img.pixels[i] = (i / 97) % 3 == 0 ? std::uint8_t(rng()) : std::uint8_t(i / 97);
    return img;
}

} // namespace

TEST_CASE("a PNG read from its specification gives back the pixels", "[png]") {
    for (int channels : {1, 3, 4})
        for (auto [w, h] : {std::pair{1, 1}, {1, 7}, {37, 5}, {300, 200}}) {
            CAPTURE(channels, w, h);
            const Image8 img = random_image(w, h, channels, std::uint32_t(w * 31 + h + channels));
            const std::vector<std::uint8_t> png = encode_png(img);
            // The signature, then chunks (big-endian length, type, data, CRC-32 of type and data): IHDR
            // first, IEND last, the image data in IDAT.
            const std::uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
            REQUIRE(png.size() > 8);
            REQUIRE(std::equal(signature, signature + 8, png.begin()));
            std::vector<std::string> types;
            std::vector<std::uint8_t> idat;
            for (size_t at = 8; at < png.size();) {
                REQUIRE(at + 12 <= png.size());
                const size_t n = be32(png, at);
                REQUIRE(at + 12 + n <= png.size());
                const std::string type(png.begin() + long(at) + 4, png.begin() + long(at) + 8);
                CHECK(be32(png, at + 8 + n) == bitwise_crc32(png.data() + at + 4, n + 4));
                if (type == "IHDR") {
                    REQUIRE(n == 13);
                    CHECK(be32(png, at + 8) == std::uint32_t(w));
                    CHECK(be32(png, at + 12) == std::uint32_t(h));
                    CHECK(int(png[at + 16]) == 8); // bits per channel
                    CHECK(int(png[at + 17]) == (channels == 1 ? 0 : channels == 3 ? 2 : 6));
                    CHECK(int(png[at + 18]) + png[at + 19] + png[at + 20] ==
                          0); // deflate, filters, no interlace
                }
                if (type == "IDAT")
                    idat.insert(idat.end(), png.begin() + long(at) + 8, png.begin() + long(at + 8 + n));
                types.push_back(type);
                at += 12 + n;
            }
            REQUIRE(types.size() >= 3);
            CHECK(types.front() == "IHDR");
            CHECK(types.back() == "IEND");
            // The zlib stream inflates (stb's own inflate) to one filter byte and the row for every row.
            int raw_n = 0;
            char* raw =
                stbi_zlib_decode_malloc(reinterpret_cast<const char*>(idat.data()), int(idat.size()), &raw_n);
            REQUIRE(raw != nullptr);
            CHECK(raw_n == h * (1 + w * channels));
            std::free(raw);
            // A decoder written from the same specification elsewhere (stb_image) reads the same pixels.
            int dw = 0, dh = 0, dc = 0;
            unsigned char* px = stbi_load_from_memory(png.data(), int(png.size()), &dw, &dh, &dc, 0);
            REQUIRE(px != nullptr);
            CHECK((dw == w && dh == h && dc == channels));
            CHECK(std::equal(img.pixels.begin(), img.pixels.end(), px));
            stbi_image_free(px);
        }
}

TEST_CASE("a PNG of an empty or malformed image is refused with what is wrong", "[png]") {
    CHECK_THROWS_WITH(encode_png(Image8{0, 4, 3, {}}), Catch::Contains("empty"));
    CHECK_THROWS_WITH(encode_png(Image8{2, 2, 2, std::vector<std::uint8_t>(8)}),
                      Catch::Contains("allowed: 1, 3 or 4"));
    CHECK_THROWS_WITH(encode_png(Image8{2, 2, 3, std::vector<std::uint8_t>(11)}),
                      Catch::Contains("11 bytes for 2 x 2 x 3"));
}

TEST_CASE("a ProjectedSonarImage's rx_beamwidths are the receive beams' -3 dB widths", "[mcap]") {
    // The oculus-m750d-lf preset forms its beams with an array: the broadside -3 dB width of its
    // sensor.azimuth_beamwidth_deg, widened as 1 / cos of each beam's azimuth (held below 10x).
    SceneDesc s = small_scene();
    apply_setting(s, "sonar.device", "oculus-m750d-lf", "test");
    apply_setting(s, "sensor.model", "device", "test");
    REQUIRE(s.sensor.beamformer == Beamformer::Array);
    REQUIRE(s.sensor.azimuth_window != AzimuthWindow::None);
    const double bw_deg = s.sensor.azimuth_beamwidth_deg;
    REQUIRE(bw_deg > 0);
    PolarImage img;
    img.beams = s.sonar.beams, img.bins = s.sonar.range_bins;
    img.level_db.assign(size_t(img.beams) * size_t(img.bins), 50.0f);
    ClipCount count;
    const auto msg =
        encode_projected_sonar_image(s, img, 0.5, "sonar", SonarDataType::Uint8, kZeroTo80, count);
    Reader c{msg, 4, 4};
    c.get<std::int32_t>(true), c.get<std::uint32_t>(true), c.str(true);
    c.get<float>(true), c.get<float>(true);
    const auto tx = c.get<std::uint32_t>(true);
    for (size_t i = 0; i < tx; ++i) c.get<float>(true);
    const auto rx = c.get<std::uint32_t>(true);
    REQUIRE(int(rx) == s.sonar.beams);
    const std::vector<double> az = sonar_grid(s.sonar)->beam_azimuths_deg();
    double widest = 0, narrowest = 1e9;
    for (size_t i = 0; i < rx; ++i) {
        const double w_deg = c.get<float>(true) * 180 / kPi;
        const double want = bw_deg / std::max(0.1, std::cos(az[i] * kPi / 180));
        CHECK(w_deg == Approx(want).epsilon(1e-5));
        widest = std::max(widest, w_deg), narrowest = std::min(narrowest, w_deg);
    }
    // Wider than the beam spacing (what the field held before), and widest at the edges of the fan.
    CHECK(narrowest > s.sonar.azimuth_fov_deg / s.sonar.beams);
    CHECK(widest > 1.5 * narrowest);
}

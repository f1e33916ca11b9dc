// The ARIS reader (core/io/aris_read) on files built here byte by byte from the vendor's header layout
// (docs/formats.md), independently of our writer, and on a recording our writer made.
#include "support.hpp"

#include "core/base/errors.hpp"
#include "core/dataset/batch.hpp"
#include "core/io/aris.hpp"
#include "core/io/aris_read.hpp"
#include "core/io/output.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>

using namespace sonarsim;
using namespace sonarsim::test;

namespace {

template <typename T> void put(std::vector<std::uint8_t>& b, size_t off, T v) {
    std::memcpy(b.data() + off, &v, sizeof v);
}

struct Spec {
    std::uint32_t ping_mode = 1; // 48 beams
    std::uint32_t samples = 10, period_us = 8, delay_us = 1300, reordered = 1;
    float sound_speed = 1480;
    int frames = 2;
};

/// Byte (sample s, beam j as stored) of frame f: a pattern every position gives differently.
std::uint8_t pattern(int f, int s, int j) {
    return std::uint8_t((f * 37 + s * 11 + j * 3) % 251 + (s == 0 && j == 0 ? 0 : 1)) *
           (s == 0 && j == 0 ? 0 : 1);
}

std::vector<std::uint8_t> make_file(const Spec& p) {
    const int beams = aris_beams_of_ping_mode(p.ping_mode);
    std::vector<std::uint8_t> b(1024, 0);
    put<std::uint32_t>(b, 0, 0x05464444);
    put<std::uint32_t>(b, 4, std::uint32_t(p.frames));
    for (int f = 0; f < p.frames; ++f) {
        std::vector<std::uint8_t> h(1024, 0);
        put<std::uint32_t>(h, 0, std::uint32_t(f));
        put<std::uint64_t>(h, 4, 1700000000000000ull + std::uint64_t(f) * 100000);
        put<std::uint32_t>(h, 12, 0x05464444);
        put<std::uint32_t>(h, 68, 12);       // ReceiverGain
        put<float>(h, 232, 1.5f + float(f)); // SonarX
        put<std::uint32_t>(h, 436, p.ping_mode);
        put<std::uint32_t>(h, 440, 1); // HF
        put<std::uint32_t>(h, 452, p.period_us);
        put<float>(h, 464, p.sound_speed);
        put<std::uint32_t>(h, 468, p.samples);
        put<std::uint32_t>(h, 476, p.delay_us);
        put<std::uint32_t>(h, 516, p.reordered);
        b.insert(b.end(), h.begin(), h.end());
        for (int s = 0; s < int(p.samples); ++s)
            for (int j = 0; j < beams; ++j) b.push_back(pattern(f, s, j));
    }
    return b;
}

} // namespace

TEST_CASE("an ARIS file built from the vendor's layout reads back sample for sample", "[aris]") {
    Spec p;
    const auto bytes = make_file(p);
    REQUIRE(aris_frame_count(bytes, "test.aris") == 2);
    for (int f = 0; f < 2; ++f) {
        const ArisFrame fr = parse_aris_frame(bytes, size_t(f), "test.aris");
        CHECK(fr.info.index == std::uint32_t(f));
        CHECK(fr.info.time_us == 1700000000000000ull + std::uint64_t(f) * 100000);
        CHECK(fr.info.beams == 48);
        CHECK(fr.info.samples == 10);
        CHECK(fr.info.high_frequency);
        CHECK(fr.info.receiver_gain_db == 12);
        CHECK(fr.info.position_m[0] == Approx(1.5 + f));
        CHECK(fr.info.window_start_m == Approx(1480 * 1300e-6 / 2));
        CHECK(fr.info.sample_length_m == Approx(1480 * 8e-6 / 2));
        REQUIRE(fr.level_db.bins == 10);
        REQUIRE(fr.level_db.beams == 48);
        for (int s = 0; s < 10; ++s)
            for (int j = 0; j < 48; ++j) {
                const std::uint8_t byte = pattern(f, s, j);
                const float level =
                    fr.level_db.at(s, 47 - j); // beam 0 is the starboard-most: the last column
                if (byte == 0)
                    CHECK(std::isinf(level));
                else
                    CHECK(level == Approx(byte * 80.0 / 255.0).epsilon(1e-6));
            }
    }
}

TEST_CASE("raw ARIS frames are put in beam order: beam = channel x pings + ping", "[aris]") {
    Spec p;
    p.ping_mode = 6; // 64 beams, 4 pings of 16 channels
    p.reordered = 0;
    const ArisFrame fr = parse_aris_frame(make_file(p), 1, "raw.aris");
    for (int s = 0; s < 10; ++s)
        for (int j = 0; j < 64; ++j) {
            const int ping = j / 16, channel = j % 16, beam = channel * 4 + ping;
            const std::uint8_t byte = pattern(1, s, j);
            const float level = fr.level_db.at(s, 63 - beam);
            if (byte == 0)
                CHECK(std::isinf(level));
            else
                CHECK(level == Approx(byte * 80.0 / 255.0).epsilon(1e-6));
        }
}

TEST_CASE("malformed ARIS files are one clear error naming the field", "[aris]") {
    const Spec p;
    auto fails_with = [](const std::vector<std::uint8_t>& b, const std::string& text) {
        CHECK_THROWS_WITH(parse_aris_frame(b, 0, "x.aris"), Catch::Contains(text));
    };
    auto b = make_file(p);
    b.pop_back();
    fails_with(b, "x.aris: frame 0: SamplesPerBeam: the file's size is not a whole number of frames");
    b = make_file(p);
    put<std::uint32_t>(b, 0, 0x04464444);
    fails_with(b, "x.aris: Version: not an ARIS DDF_05 file");
    b = make_file(p);
    put<std::uint32_t>(b, 1024 + 436, 7);
    fails_with(b, "x.aris: frame 0: PingMode: ping mode 7 is not one we know; allowed: 1, 3, 6, 9");
    b = make_file(p);
    put<float>(b, 1024 + 464, 0.f);
    fails_with(b, "x.aris: frame 0: SoundSpeed");
    b = make_file(p);
    CHECK_THROWS_WITH(parse_aris_frame(b, 2, "x.aris"), "x.aris: frame: frame 2 asked for; the file holds 2");
    fails_with(std::vector<std::uint8_t>(100, 0), "x.aris: too short for an ARIS file");
    // A second frame whose header disagrees with the first's.
    b = make_file(p);
    put<std::uint32_t>(b, 1024 + 1024 + 48 * 10 + 436, 3);
    CHECK_THROWS_WITH(parse_aris_frame(b, 1, "x.aris"), Catch::Contains("frame 1: "));
}

TEST_CASE("a recording our writer made reads back frame by frame", "[aris]") {
    const std::string dir = batch_out("aris_read");
    const SceneDesc scene = small_aris_scene();
    const Trajectory t = line_trajectory("0.3,2.4,0.9,0.4,2.3,0.9,3", {-1, 30, -39}, 6.5, "test");
    prepare_dataset(dir, scene, t);
    run_batch(dir, {});
    const std::string path = dir + "/out.aris";
    write_aris(path, scene, t, dataset_images(dir, 3, "--aris"), ByteMapping{0, 80, false}, "--aris");
    REQUIRE(aris_frame_count(path) == 3);
    for (size_t k = 0; k < 3; ++k) {
        const ArisFrame f = read_aris_frame(path, k);
        CHECK(f.info.index == k);
        CHECK(f.level_db.beams == 48);
        CHECK(f.level_db.bins == scene.sonar.range_bins);
        CHECK(f.info.position_m[0] == Approx(t[k].pose.position_m[0]));
        size_t lit = 0;
        for (float v : f.level_db.level_db) lit += std::isfinite(v);
        CHECK(lit > 100);
    }
    CHECK_THROWS_AS(read_aris_frame(dir + "/missing.aris", 0), InputError);
}

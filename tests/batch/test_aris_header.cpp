// ARIS headers a vendor tool would believe: the mode (PingMode, FrequencyHiLow, TheSystemType) from the
// device and the frequency, never from the beam count alone; the water's sound speed; every field within
// the vendor's documented range (file SDK, FrameHeader.h), read back as its layout says; the samples at the
// ranges the header implies; and the scenes no ARIS file can hold refused, naming the key.
#include "support.hpp"

#include "core/base/build_info.hpp"
#include "core/base/errors.hpp"
#include "core/grid/beam_tables.hpp"
#include "core/dataset/batch.hpp"
#include "core/dataset/export.hpp"
#include "core/data/trajectory.hpp"
#include "core/io/aris.hpp"
#include "core/io/aris_read.hpp"
#include "core/shading/physics.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <limits>

using namespace sonarsim;
using namespace sonarsim::test;

namespace {

SceneDesc with(SceneDesc s, std::initializer_list<const char*> sets) {
    for (const char* set : sets) apply_setting_text(s, set, "test");
    return s;
}

} // namespace

TEST_CASE("ARIS files hold only the beam counts and frequencies ARIS modes have", "[aris]") {
    const SceneDesc s = small_aris_scene();
    CHECK_THROWS_WITH(check_aris(with(s, {"sonar.beams=100"}), "scene.json"),
                      "scene.json: sonar.beams: an ARIS file holds 48, 64, 96 or 128 beams, got 100");
    for (const char* ok : {"sonar.beams=48", "sonar.frequency_khz=700", "sonar.frequency_khz=1100"})
        CHECK_NOTHROW(check_aris(with(s, {ok}), "scene.json"));
    CHECK_NOTHROW(check_aris(with(s, {"sonar.beams=64", "sonar.frequency_khz=1800"}), "s"));
    CHECK_NOTHROW(check_aris(with(s, {"sonar.beams=96", "sonar.frequency_khz=1800"}), "s"));
    CHECK_NOTHROW(check_aris(with(s, {"sonar.beams=128", "sonar.frequency_khz=3000"}), "s"));
    // 64 beams are ARIS 3000 LF: 3000 kHz is 67 % off its 1800 kHz.
    CHECK_THROWS_WITH(check_aris(with(s, {"sonar.beams=64", "sonar.frequency_khz=3000"}), "scene.json"),
                      "scene.json: sonar.frequency_khz: 3000 kHz is no ARIS mode of 64 beams: they are the "
                      "ARIS 3000 LF mode at 1800 kHz (allowed within 25 %); set sonar.frequency_khz=1800 or "
                      "sonar.device=aris3000-lf");
    CHECK_THROWS_WITH(
        check_aris(with(s, {"sonar.beams=128", "sonar.frequency_khz=1200"}), "--aris"),
        Catch::Contains("--aris: sonar.frequency_khz: 1200 kHz is no ARIS mode of 128 beams: they "
                        "are the ARIS 3000 HF mode at 3000 kHz"));
    // 2300 kHz is 28 % above 1800; 2200 kHz 22 %.
    CHECK_THROWS_AS(check_aris(with(s, {"sonar.beams=96", "sonar.frequency_khz=2300"}), "s"), InputError);
    CHECK_NOTHROW(check_aris(with(s, {"sonar.beams=96", "sonar.frequency_khz=2200"}), "s"));
    // A DIDSON is no ARIS: its beams would be read with the ARIS 1800's lens table.
    CHECK_THROWS_WITH(check_aris(with(s, {"sonar.device=didson300-hf"}), "scene.json"),
                      Catch::StartsWith("scene.json: sonar.device: didson300-hf is a DIDSON") &&
                          Catch::Contains("write --mcap instead"));
    // An ARIS preset fixes the system: the ARIS 3000 has no 96-beam mode.
    CHECK_THROWS_WITH(
        check_aris(with(s, {"sonar.device=aris3000-hf", "sonar.beams=96"}), "scene.json"),
        "scene.json: sonar.beams: an ARIS file of the aris3000-hf preset holds 128 or 64 beams, got 96");
}

namespace {

/// What each ARIS preset's recordings must say: PingMode, FrequencyHiLow, TheSystemType, beams, and the
/// system's maxima of CyclePeriod, SamplePeriod, SampleStartDelay and PulseWidth [us] (Sound Metrics'
/// integration SDK, SonarConfig.fs).
struct PresetMode {
    const char* preset;
    std::uint32_t ping_mode, high_frequency, system_type;
    int beams;
    std::uint32_t max_cycle_us, max_sp_us, max_ssd_us, max_pw_us;
};
const PresetMode kPresets[] = {{"aris3000-hf", 9, 1, 1, 128, 40000, 26, 18000, 24},
                               {"aris3000-lf", 6, 0, 1, 64, 40000, 26, 18000, 24},
                               {"aris1800-hf", 3, 1, 0, 96, 80000, 32, 36000, 40},
                               {"aris1800-lf", 1, 0, 0, 48, 80000, 32, 36000, 40},
                               {"aris1200", 1, 1, 2, 48, 150000, 40, 60000, 80}};

/// A synthetic level profile: smooth in range, a little different per beam, nothing echoing in every
/// 17th bin.
PolarImage profile(const SonarParams& sonar) {
    PolarImage img;
    img.beams = sonar.beams, img.bins = sonar.range_bins;
    for (int i = 0; i < img.bins; ++i)
        for (int b = 0; b < img.beams; ++b)
            img.level_db.push_back(i % 17 == 5 ? -std::numeric_limits<float>::infinity()
                                               : float(40 + 30 * std::sin(i * 0.05) + 0.05 * b));
    return img;
}

} // namespace

TEST_CASE("every ARIS preset's recording has its mode, the water's sound speed and documented ranges",
          "[aris]") {
    for (const PresetMode& m : kPresets) {
        INFO(m.preset);
        const SceneDesc s =
            with(small_scene(), {("sonar.device=" + std::string(m.preset)).c_str(), "sensor.model=device"});
        REQUIRE(s.sonar.beams == m.beams);
        const std::string dir = batch_out(std::string("aris_header_") + m.preset);
        std::filesystem::create_directories(dir);
        const std::string path = dir + "/p.aris";
        const Trajectory t = line_trajectory("0.3,2.4,0.9,0.4,2.3,0.9,2", {-1, 30, -39}, 5, "test");
        const PolarImage img = profile(s.sonar);
        write_aris(
            path, s, t, [&](size_t) { return img; }, ByteMapping{0, 80, false}, "--aris");
        const auto bytes = file_bytes(path);
        REQUIRE(aris_frame_count(path) == 2);
        const ArisFrame f = read_aris_frame(path, 1);
        const auto frame1 = bytes.begin() + 1024 + long(1024 + f.info.beams * f.info.samples);
        const std::vector<std::uint8_t> h(frame1, frame1 + 1024);
        CHECK(f.info.ping_mode == m.ping_mode);
        CHECK(f.info.high_frequency == bool(m.high_frequency));
        CHECK(header_field<std::uint32_t>(h, 440) == m.high_frequency);
        CHECK(header_field<std::uint32_t>(h, 484) == m.system_type); // TheSystemType
        const double c = sound_speed_m_s(s.water.temperature_c, s.water.depth_m);
        CHECK(header_field<float>(h, 464) == float(c));
        // The system's limits (SonarConfig.fs): SamplePeriod, SampleStartDelay, PulseWidth and CyclePeriod
        // from 4, 930, 4 and 1802 us to the system's maxima; 128-4096 samples per beam.
        const std::uint32_t sp = header_field<std::uint32_t>(h, 452),
                            ssd = header_field<std::uint32_t>(h, 476);
        const std::uint32_t pw = header_field<std::uint32_t>(h, 444),
                            cp = header_field<std::uint32_t>(h, 448);
        const std::uint32_t n = header_field<std::uint32_t>(h, 468);
        const double bin = (s.sonar.range_max_m - s.sonar.range_min_m) / s.sonar.range_bins;
        CHECK(sp == std::uint32_t(std::round(2 * bin / c * 1e6)));
        CHECK(sp >= 4);
        CHECK(sp <= m.max_sp_us);
        CHECK(ssd >= 930);
        CHECK(ssd <= m.max_ssd_us);
        CHECK(ssd == std::uint32_t(std::round(2 * (s.sonar.range_min_m + bin / 2) / c * 1e6)));
        CHECK(pw == std::uint32_t(std::round(2 * s.sensor.range_resolution_m / c * 1e6)));
        CHECK(s.sensor.range_resolution_m > 0);
        CHECK(pw >= 4);
        CHECK(pw <= m.max_pw_us);
        CHECK(n >= 128);
        CHECK(n <= 4096);
        CHECK(cp == ssd + sp * n + 360);
        CHECK(cp >= 1802);
        CHECK(cp <= m.max_cycle_us);
        CHECK(header_field<float>(h, 420) == float(1e6 / sp)); // SampleRate
        const double sample_m = sp * 1e-6 * double(float(c)) / 2;
        // The samples cover the window, one fewer where the last would end past the system's (next test).
        CHECK(std::abs(n * sample_m - (s.sonar.range_max_m - s.sonar.range_min_m)) <= 1.5 * sample_m);
        CHECK(header_field<float>(h, 52) == Approx(ssd * 1e-6 * double(float(c)) / 2).epsilon(1e-6));
        CHECK(header_field<float>(h, 56) == Approx(n * sample_m).epsilon(1e-6));
        CHECK(header_field<std::uint32_t>(bytes, 24) == n);
        CHECK(header_field<std::uint64_t>(bytes, 424) == bytes.size()); // FileSize
        // FrameRate [frames/s]: 5 Hz in every frame, frame 0 (from the interval to the next) too.
        const std::vector<std::uint8_t> h0(bytes.begin() + 1024, bytes.begin() + 2048);
        CHECK(header_field<float>(h0, 460) == Approx(5));
        CHECK(header_field<float>(h, 460) == Approx(5));

        // The samples sit at the ranges the header implies: the profile, resampled there, read back.
        size_t off = 0, finite = 0;
        for (int j = 0; j < f.level_db.bins; ++j)
            for (int col = 0; col < f.level_db.beams; ++col) {
                const double r = f.info.window_start_m + j * f.info.sample_length_m;
                const float want = level_at_range(img, col, s.sonar.range_min_m, s.sonar.range_max_m, r);
                const float got = f.level_db.at(j, col);
                if (!std::isfinite(want) || !std::isfinite(got)) { // byte 0: nothing above 0 dB
                    off += std::isfinite(want) && want > 0.5 * 80 / 255;
                    off += std::isfinite(got);
                    continue;
                }
                ++finite;
                off += std::abs(got - want) > 0.5 * 80 / 255 + 1e-3;
            }
        CHECK(off == 0);
        CHECK(finite > size_t(f.level_db.bins) * size_t(f.level_db.beams) / 2);
    }
}

TEST_CASE("ARIS grids outside the system's limits are one input error naming the key and the limit",
          "[aris]") {
    // Sound Metrics' integration SDK (SonarConfig.fs): every system SamplePeriod from 4 us, SampleStartDelay
    // from 930 us, PulseWidth from 4 us, CyclePeriod from 1802 us, 128-4096 samples per beam; the maxima per
    // system (SP, SSD, PW, CP in us; window start and end in m): ARIS 1800 32, 36000, 40, 80000, 25, 50; ARIS
    // 3000 26, 18000, 24, 40000, 12, 20; ARIS 1200 40, 60000, 80, 150000, 40, 100.
    const SceneDesc s = small_aris_scene(); // 1-5 m, 256 bins, 48 beams at 1200 kHz: ARIS 1200 HF
    CHECK_NOTHROW(check_aris(s, "scene.json"));
    const SceneDesc a3000 = with(s, {"sonar.device=aris3000-hf"}),
                    a1800 = with(s, {"sonar.device=aris1800-hf"});
    // SampleStartDelay < 930 us: about 0.7 m of water before the first sample.
    CHECK_THROWS_WITH(check_aris(with(s, {"sonar.range_min_m=0.3"}), "scene.json"),
                      Catch::StartsWith("scene.json: sonar.range_min_m: an ARIS 1200 starts sampling 930-") &&
                          Catch::Contains("range_min_m from 0.6"));
    // Window start: an ARIS 3000's at most 12 m.
    CHECK_THROWS_WITH(
        check_aris(with(a3000, {"sonar.range_min_m=12.5", "sonar.range_max_m=14", "sonar.range_bins=256"}),
                   "s"),
        Catch::StartsWith("s: sonar.range_min_m: an ARIS 3000 starts sampling") &&
            Catch::Contains("a window start of at most 12 m"));
    // SamplePeriod: an ARIS 3000 samples every 26 us at most, an ARIS 1800 32, an ARIS 1200 40: 120 bins over
    // 4 m are 33.3 mm, 44.7 us.
    for (const auto& [scene, limit] : {std::pair{s, "4-40 us"}, {a1800, "4-32 us"}, {a3000, "4-26 us"}})
        CHECK_THROWS_WITH(
            check_aris(with(scene, {"sonar.range_min_m=1", "sonar.range_max_m=5", "sonar.range_bins=120"}),
                       "s"),
            Catch::StartsWith("s: sonar.range_bins: an ARIS ") &&
                Catch::Contains(std::string("samples every ") + limit + " (SamplePeriod)"));
    // 4096 bins over 4 m are 1.3 us, below every system's 4 us.
    CHECK_THROWS_WITH(check_aris(with(s, {"sonar.range_bins=4096"}), "scene.json"),
                      Catch::StartsWith("scene.json: sonar.range_bins: an ARIS 1200 samples every 4-40 us"));
    // Samples per beam: 100 bins of 40 mm over 4 m (SamplePeriod 54 us: too long) ... 4 m at 26 us is 154
    // samples; 0.9 m at 13 us (121 samples) is too few.
    CHECK_THROWS_WITH(
        check_aris(with(a3000, {"sonar.range_min_m=1", "sonar.range_max_m=1.9", "sonar.range_bins=121"}),
                   "s"),
        Catch::StartsWith("s: sonar.range_bins: an ARIS frame holds 128-4096 samples per beam"));
    // PulseWidth: an ARIS 1200 pulse is at most 80 us, an ARIS 3000's 24 us: 0.02 m is 27 us.
    CHECK_THROWS_WITH(check_aris(with(s, {"sensor.range_resolution_m=0.1"}), "s"),
                      Catch::StartsWith("s: sensor.range_resolution_m: an ARIS 1200 pulse is 4-80 us long"));
    CHECK_NOTHROW(check_aris(with(s, {"sensor.range_resolution_m=0.02"}), "s"));
    CHECK_THROWS_WITH(check_aris(with(a3000, {"sonar.range_min_m=1", "sonar.range_max_m=5",
                                              "sonar.range_bins=256", "sensor.range_resolution_m=0.02"}),
                                 "s"),
                      Catch::StartsWith("s: sensor.range_resolution_m: an ARIS 3000 pulse is 4-24 us long"));
    // Window end: an ARIS 3000's at most 20 m, so not out to 30 m.
    CHECK_THROWS_WITH(
        check_aris(with(a3000, {"sonar.range_min_m=5", "sonar.range_max_m=30", "sonar.range_bins=2048"}),
                   "s"),
        Catch::StartsWith("s: sonar.range_max_m: an ARIS 3000's window ends at most 20 m"));
    // CyclePeriod's limits follow from the others: at least 930 + 128 x 4 + 360 = 1802 us, and a window
    // ending within the system's is heard within its longest cycle (20 m: 27 ms of 40; 50 m: 67 of 80).
}

TEST_CASE("every ARIS preset's window ends within its system's, one sample short where it would not",
          "[aris]") {
    // aris3000-lf (5-20 m) and aris1800-lf (15-50 m) end at their systems' window ends: the samples that
    // cover the window would end 12 and 16 mm past them, so the file holds one fewer and says so.
    const struct {
        const char* preset;
        double window_end_max_m;
        bool shortened;
    } presets[] = {{"aris3000-hf", 20, false},
                   {"aris3000-lf", 20, true},
                   {"aris1800-hf", 50, false},
                   {"aris1800-lf", 50, true},
                   {"aris1200", 100, false}};
    for (const auto& p : presets) {
        INFO(p.preset);
        const SceneDesc s = with(small_scene(), {("sonar.device=" + std::string(p.preset)).c_str()});
        const std::string dir = batch_out(std::string("aris_window_end_") + p.preset);
        std::filesystem::create_directories(dir);
        const std::string path = dir + "/p.aris";
        const Trajectory t = line_trajectory("0.3,2.4,0.9,0.4,2.3,0.9,1", {-1, 30, -39}, 1, "test");
        const PolarImage img = profile(s.sonar);
        const ExportReport r = write_aris(
            path, s, t, [&](size_t) { return img; }, ByteMapping{0, 80, false}, "--aris");
        const ArisFrame f = read_aris_frame(path, 0);
        const double end_m = f.info.window_start_m + f.info.samples * f.info.sample_length_m;
        CHECK(end_m <= p.window_end_max_m + 1e-6);
        CHECK(end_m > s.sonar.range_max_m - f.info.sample_length_m - 1e-6);
        CHECK(std::count_if(r.notes.begin(), r.notes.end(), [](const std::string& n) {
                  return n.find("the window ends") != std::string::npos;
              }) == (p.shortened ? 1 : 0));
    }
}

TEST_CASE(
    "batch --aris renders on the device's samples: the file holds the rendered levels, not a resampling",
    "[aris]") {
    for (const char* preset : {"aris3000-hf", "aris3000-lf", "aris1800-lf", "aris1200"}) {
        INFO(preset);
        const SceneDesc asked = with(small_scene(), {(std::string("sonar.device=") + preset).c_str()});
        std::string note;
        const SceneDesc s = on_aris_samples(asked, "--aris", note);
        CHECK_FALSE(note.empty()); // the presets' own grids are not the samples
        std::string again;
        CHECK(on_aris_samples(s, "--aris", again).sonar.range_min_m == s.sonar.range_min_m);
        CHECK(again.empty());

        const std::string dir = batch_out(std::string("aris_on_samples_") + preset);
        std::filesystem::create_directories(dir);
        const Trajectory t = line_trajectory("0.3,2.4,0.9,0.4,2.3,0.9,1", {-1, 30, -39}, 1, "test");
        const ByteMapping mapping{0, 80, false};
        const PolarImage img = profile(s.sonar);
        const ExportReport r = write_aris(
            dir + "/s.aris", s, t, [&](size_t) { return img; }, mapping, "--aris");
        for (const std::string& n : r.notes) CHECK(n.find("resampled") == std::string::npos);
        const ExportReport ra = write_aris(
            dir + "/a.aris", asked, t, [&](size_t) { return profile(asked.sonar); }, mapping, "--aris");
        CHECK(std::count_if(ra.notes.begin(), ra.notes.end(), [](const std::string& n) {
                  return n.find("resampled") != std::string::npos;
              }) == 1);
        // The same device grid either way, now one bin per sample.
        const ArisFrame f = read_aris_frame(dir + "/s.aris", 0), fa = read_aris_frame(dir + "/a.aris", 0);
        CHECK(f.info.samples == fa.info.samples);
        CHECK(f.info.sample_period_us == fa.info.sample_period_us);
        CHECK(f.info.sample_start_delay_us == fa.info.sample_start_delay_us);
        REQUIRE(f.info.samples == s.sonar.range_bins);
        CHECK(f.info.window_start_m ==
              Approx(s.sonar.range_min_m + f.info.sample_length_m / 2).epsilon(1e-9));
        // Every sample is its bin's byte.
        ClipCount count;
        const std::vector<std::uint8_t> expected = image_bytes(img, mapping, count);
        size_t same = 0;
        for (int j = 0; j < img.bins; ++j)
            for (int b = 0; b < img.beams; ++b) {
                const float level = f.level_db.at(j, b);
                const int byte = level > -INFINITY ? int(std::lround(level * 255 / 80)) : 0;
                same += byte == expected[size_t(j) * size_t(img.beams) + size_t(b)];
            }
        CHECK(same == size_t(img.bins) * size_t(img.beams));
    }
}

TEST_CASE("ARIS ReceiverGain is the sensor's gain, the nearest whole dB in 0-24 and said so", "[aris]") {
    const struct {
        const char* gain;
        std::uint32_t written;
        bool note;
    } cases[] = {{"12", 12, false},  {"0", 0, false},  {"24", 24, false},
                 {"12.4", 12, true}, {"30", 24, true}, {"-6", 0, true}};
    for (const auto& c : cases) {
        INFO(c.gain);
        const SceneDesc s = with(small_scene(), {"sonar.device=aris3000-hf", "sensor.model=device",
                                                 (std::string("sensor.gain_db=") + c.gain).c_str()});
        const std::string dir = batch_out("aris_receiver_gain");
        std::filesystem::create_directories(dir);
        const std::string path = dir + "/g.aris";
        const Trajectory t = line_trajectory("0.3,2.4,0.9,0.4,2.3,0.9,1", {-1, 30, -39}, 1, "test");
        const PolarImage img = profile(s.sonar);
        const ExportReport r = write_aris(
            path, s, t, [&](size_t) { return img; }, ByteMapping{0, 80, false}, "--aris");
        CHECK(read_aris_frame(path, 0).info.receiver_gain_db == c.written);
        CHECK(std::count_if(r.notes.begin(), r.notes.end(), [](const std::string& n) {
                  return n.find("ReceiverGain") != std::string::npos;
              }) == (c.note ? 1 : 0));
    }
}

TEST_CASE("ARIS FrameTime is the dataset's start plus t, the start kept when a run resumes", "[aris]") {
    const std::string dir = batch_out("aris_start_time");
    const SceneDesc s = small_aris_scene();
    const Trajectory t = line_trajectory("0.3,2.4,0.9,0.4,2.3,0.9,2", {-1, 30, -39}, 5, "test");
    prepare_dataset(dir, s, t);
    const double start = dataset_start_time_s(dir);
    CHECK(start == 1767225600); // 2026-01-01 00:00:00 UTC: never the wall clock unless asked for
    SceneDesc later = s;
    later.exports.start_time_s = 1.7e9;
    prepare_dataset(dir, later, t); // a resumed run keeps the recorded start
    CHECK(dataset_start_time_s(dir) == start);
    run_batch(dir, {});

    export_dataset(dir, dir + "/a.aris", dataset_container("--aris"), false, ExportParams{}, "--aris");
    ExportParams pinned;
    pinned.start_time_s = 1700000000.25;
    export_dataset(dir, dir + "/b.aris", dataset_container("--aris"), false, pinned, "--aris");
    for (size_t k = 0; k < 2; ++k) {
        CHECK(read_aris_frame(dir + "/a.aris", k).info.time_us ==
              std::uint64_t(std::llround((start + t[k].t_s) * 1e6)));
        CHECK(read_aris_frame(dir + "/b.aris", k).info.time_us ==
              1700000000250000ull + std::uint64_t(std::llround(t[k].t_s * 1e6)));
    }
    CHECK(t[1].t_s > 0);
    const auto b = file_bytes(dir + "/b.aris");
    CHECK(std::string(reinterpret_cast<const char*>(b.data() + 48)) == "2023-11-14 22:13:20 UTC"); // strDate

    // A start given when the dataset is first prepared is the one recorded.
    const std::string dir2 = batch_out("aris_start_time_given");
    prepare_dataset(dir2, later, t);
    CHECK(dataset_start_time_s(dir2) == 1.7e9);
}

TEST_CASE("the same batch writes the same ARIS file, and its dataset says what made it", "[aris]") {
    SceneDesc s = small_aris_scene();
    s.source_file = "scenes/small.json";
    const Trajectory t = line_trajectory("0.3,2.4,0.9,0.4,2.3,0.9,2", {-1, 30, -39}, 5, "test");
    std::vector<std::vector<std::uint8_t>> files;
    for (const char* name : {"aris_repeat_a", "aris_repeat_b"}) {
        const std::string dir = batch_out(name);
        std::filesystem::remove_all(dir);
        prepare_dataset(dir, s, t);
        run_batch(dir, {});
        export_dataset(dir, dir + "/x.aris", dataset_container("--aris"), false, ExportParams{}, "--aris");
        files.push_back(file_bytes(dir + "/x.aris"));
        const auto text = file_bytes(dir + "/dataset.json");
        const json d = json::parse(std::string(text.begin(), text.end()));
        CHECK(d["program"]["name"] == "sonarsim");
        CHECK(d["program"]["version"] == program_version());
        CHECK(d["program"]["commit"] == program_commit());
        CHECK(std::string(program_commit()).size() >= 7);
        CHECK(d["scene_file"] == std::filesystem::absolute("scenes/small.json").lexically_normal().string());
    }
    REQUIRE(files[0].size() > 2048);
    CHECK(files[0] == files[1]); // byte for byte, the file header's date included
}

TEST_CASE("an ARIS file holds each beam of a table at the device's number of it", "[aris][beam_table]") {
    // aris3000-hf: the vendor's 128-beam table; sonarsim beam k is ARIS beam 127 - k (ARIS numbers from
    // starboard). One beam lit: its bytes must sit in the device's column, and read back in ours.
    const SceneDesc s = with(small_scene(), {"sonar.device=aris3000-hf", "sensor.model=device"});
    REQUIRE(s.sonar.beam_table == "aris3000_128");
    const BeamTable& table = *find_beam_table("aris3000_128");
    const int N = s.sonar.beams, k = 10;
    REQUIRE(table.device_beam[size_t(k)] == N - 1 - k);
    PolarImage img;
    img.beams = N, img.bins = s.sonar.range_bins;
    img.level_db.assign(size_t(N) * size_t(img.bins), -std::numeric_limits<float>::infinity());
    for (int i = 0; i < img.bins; ++i) img.level_db[size_t(i) * size_t(N) + size_t(k)] = 60.0f;
    const std::string dir = batch_out("aris_beam_table");
    std::filesystem::create_directories(dir);
    const std::string path = dir + "/t.aris";
    const Trajectory t = line_trajectory("0.3,2.4,0.9,0.4,2.3,0.9,1", {-1, 30, -39}, 5, "test");
    write_aris(
        path, s, t, [&](size_t) { return img; }, ByteMapping{0, 80, false}, "--aris");
    const ArisFrame f = read_aris_frame(path, 0);
    REQUIRE(f.info.beams == N);
    const auto bytes = file_bytes(path);
    const size_t data = 1024 + 1024, samples = size_t(f.info.samples);
    std::vector<int> lit(static_cast<size_t>(N), 0);
    for (size_t r = 0; r < samples; ++r)
        for (int b = 0; b < N; ++b) lit[size_t(b)] += bytes[data + r * size_t(N) + size_t(b)] != 0;
    for (int b = 0; b < N; ++b) {
        INFO("ARIS beam " << b);
        CHECK((lit[size_t(b)] > 0) == (b == table.device_beam[size_t(k)]));
    }
    int ours = 0, others = 0; // read back: only our beam k
    for (int r = 0; r < f.level_db.bins; ++r)
        for (int b = 0; b < N; ++b)
            if (std::isfinite(f.level_db.at(r, b))) ++(b == k ? ours : others);
    CHECK(ours == lit[size_t(table.device_beam[size_t(k)])]);
    CHECK(others == 0);
}

TEST_CASE("an ARIS recording is never faster than its mode images a frame", "[aris]") {
    // The frame times ARIS tools accept (issue 46, checked with the vendor's validation): CyclePeriod x
    // pings per frame of each preset's own window (aris3000-lf and aris1800-lf one sample shorter than
    // there, 4 x 20 and 3 x 23 us less: their windows end within their systems').
    const struct {
        const char* preset;
        double frame_ms;
    } modes[] = {
        {"aris3000-lf", 108.82}, {"aris1800-hf", 123.0}, {"aris1800-lf", 202.43}, {"aris1200", 101.8}};
    for (const auto& m : modes) {
        INFO(m.preset);
        const SceneDesc s = with(small_scene(), {("sonar.device=" + std::string(m.preset)).c_str()});
        auto at_rate = [&](double hz) {
            return line_trajectory("0.3,2.4,0.9,0.4,2.3,0.9,3", {-1, 30, -39}, hz, "test");
        };
        CHECK_NOTHROW(check_aris_frame_times(s, at_rate(1000 / (m.frame_ms + 0.15)), "scene.json", "--rate"));
        try {
            check_aris_frame_times(s, at_rate(1000 / (m.frame_ms - 0.15)), "scene.json", "--rate");
            FAIL("a rate faster than the device was accepted");
        } catch (const InputError& e) {
            const std::string what = e.what(), tag = "the fastest it allows is ";
            CHECK(what.rfind("--rate: frame 1 comes ", 0) == 0);
            REQUIRE(what.find(tag) != std::string::npos);
            const double fastest_hz = std::stod(what.substr(what.find(tag) + tag.size()));
            CHECK(fastest_hz <= 1000 / (m.frame_ms - 0.02)); // rounded down: a rate it names is allowed
            CHECK(fastest_hz > 1000 / m.frame_ms - 0.015);
        }
    }
    // At most 15 frames/s whatever the window: the ARIS 3000 HF's 1-5 m frame is 8 x 7.1 ms = 57 ms.
    const SceneDesc hf = with(small_aris_scene(), {"sonar.device=aris3000-hf", "sonar.range_min_m=1",
                                                   "sonar.range_max_m=5", "sonar.range_bins=512"});
    auto line_at = [](double hz) {
        return line_trajectory("0.3,2.4,0.9,0.4,2.3,0.9,3", {-1, 30, -39}, hz, "t");
    };
    CHECK_NOTHROW(check_aris_frame_times(hf, line_at(15), "s", "--rate"));
    CHECK_THROWS_WITH(check_aris_frame_times(hf, line_at(16), "s", "--rate"),
                      Catch::Contains("(at most 15 frames/s)") &&
                          Catch::EndsWith("the fastest it allows is 15 frames/s"));
    // A trajectory file's own times are judged the same way, naming the file.
    Trajectory t = line_trajectory("0.3,2.4,0.9,0.4,2.3,0.9,3", {-1, 30, -39}, 5, "test");
    t[2].t_s = t[1].t_s + 0.05;
    CHECK_THROWS_WITH(
        check_aris_frame_times(with(small_scene(), {"sonar.device=aris1200"}), t, "s", "traj.csv"),
        Catch::StartsWith("traj.csv: frame 2 comes 50 ms after the one before"));
}

// 8-bit exports fit the byte range: the shipwreck of README's example with the default mapping (export.auto)
// is not saturated and not a binary mask, an explicit mapping is honoured byte for byte, and the clipped
// samples reported (the returned report, FILE.json, the headers) are the ones counted in the file, read
// as its specification says.
#include "support.hpp"

#include "core/base/errors.hpp"
#include "core/dataset/batch.hpp"
#include "core/dataset/export.hpp"
#include "core/io/output.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>
#include <set>

using namespace sonarsim;
using namespace sonarsim::test;

namespace {

/// Per frame of an ARIS file: its frame header and its bytes (sample-major, beam 0 starboard-most).
struct ArisFrame {
    std::vector<std::uint8_t> header, samples;
};

std::vector<ArisFrame> read_aris(const std::string& path, size_t beams) {
    const auto b = file_bytes(path);
    REQUIRE(b.size() > 2048);
    REQUIRE(at<std::uint32_t>(b, 16) == beams);
    const size_t bins = at<std::uint32_t>(b, 1024 + 468); // SamplesPerBeam
    REQUIRE(at<std::uint32_t>(b, 24) == bins);
    const size_t frame = 1024 + beams * bins;
    REQUIRE((b.size() - 1024) % frame == 0);
    std::vector<ArisFrame> out;
    for (size_t p = 1024; p < b.size(); p += frame)
        out.push_back({{b.begin() + long(p), b.begin() + long(p + 1024)},
                       {b.begin() + long(p + 1024), b.begin() + long(p + frame)}});
    return out;
}

/// The level of sample s, ARIS beam i, in the image of frame k (its last column is ARIS beam 0), at the
/// range the frame header gives sample s: (SampleStartDelay + s SamplePeriod) SoundSpeed / 2.
float level_of(const PolarImage& img, const SceneDesc& scene, const ArisFrame& f, size_t sample_beam_index) {
    const size_t beams = size_t(img.beams);
    const size_t s = sample_beam_index / beams, i = sample_beam_index % beams;
    const double c = header_field<float>(f.header, 464);
    const double r = (header_field<std::uint32_t>(f.header, 476) +
                      double(s) * header_field<std::uint32_t>(f.header, 452)) *
                     1e-6 * c / 2;
    return level_at_range(img, int(beams - 1 - i), scene.sonar.range_min_m, scene.sonar.range_max_m, r);
}

/// README's example: the shipwreck at 48 beams (ARIS 1200 HF), two frames of a circle around it.
struct Wreck {
    std::string dir;
    SceneDesc scene;
    std::vector<PolarImage> images;
    explicit Wreck(const std::string& name) : dir(batch_out(name)) {
        scene = load_scene(SONARSIM_ASSETS "/scenes/shipwreck.json");
        apply_setting(scene, "sonar.beams", 48, "test");        // ARIS 1200 HF at the scene's 1200 kHz
        apply_setting(scene, "sonar.range_bins", 1000, "test"); // SamplePeriod 32 us: ARIS 1200 allows 40
        validate_scene(scene, "test");
        prepare_dataset(dir, scene, circle_trajectory("0,0,0,17,6,2", 9, "test")); // ARIS 1200: 9.82 fps
        run_batch(dir, {});
        for (size_t k = 0; k < 2; ++k) {
            const auto b = file_bytes(frame_prefix(dir, k) + ".npy");
            images.push_back(decode_npy(b, "npy"));
        }
    }
};

/// One directory per test case: ctest runs them as parallel processes.
const Wreck& wreck(const std::string& name) {
    static const Wreck w(name);
    return w;
}

} // namespace

TEST_CASE("the shipwreck exported with the default mapping fits the byte range", "[exports][aris]") {
    const Wreck& w = wreck("exports_wreck_auto");
    const std::string path = w.dir + "/wreck.aris";
    const ExportParams defaults; // export.auto
    REQUIRE(defaults.auto_range);
    const ExportReport report =
        export_dataset(w.dir, path, dataset_container("--aris"), false, defaults, "--aris");
    const auto frames = read_aris(path, 48);
    REQUIRE(frames.size() == 2);

    // The mapping: byte 255 at the 99.5th percentile of both frames' finite levels (the test's own sort),
    // rounded up to 0.1 dB, 80 dB above byte 0; in every frame header's UserValue1 and UserValue2.
    std::vector<float> levels;
    for (auto& img : w.images)
        for (float v : img.level_db)
            if (std::isfinite(v)) levels.push_back(v);
    std::sort(levels.begin(), levels.end());
    const double p995 = levels[size_t(std::ceil(0.995 * double(levels.size()))) - 1];
    CHECK(report.mapping.automatic);
    CHECK(report.mapping.hi_db >= p995 - 1e-3);
    CHECK(report.mapping.hi_db <= p995 + 0.1 + 0.011);
    CHECK(report.mapping.hi_db - report.mapping.lo_db == Approx(80));

    size_t samples = 0, at_255 = 0, with_level = 0, level_at_0 = 0;
    std::set<int> distinct;
    for (size_t k = 0; k < 2; ++k) {
        const ArisFrame& f = frames[k];
        CHECK(at<float>(f.header, 92) == float(report.mapping.lo_db));
        CHECK(at<float>(f.header, 96) == float(report.mapping.hi_db));
        size_t frame_255 = 0, frame_0 = 0;
        for (size_t i = 0; i < f.samples.size(); ++i) {
            const std::uint8_t b = f.samples[i];
            const bool has_level = std::isfinite(level_of(w.images[k], w.scene, f, i));
            distinct.insert(b);
            frame_255 += b == 255;
            frame_0 += has_level && b == 0;
            with_level += has_level;
        }
        CHECK(report.frames[k].high == frame_255);
        CHECK(report.frames[k].low == frame_0);
        samples += f.samples.size(), at_255 += frame_255, level_at_0 += frame_0;
    }
    INFO("at 255: " << at_255 << ", with a level at 0: " << level_at_0 << " of " << samples << " samples ("
                    << with_level << " with a level), " << distinct.size() << " distinct bytes");
    CHECK(double(at_255) <= 0.01 * double(samples)); // the fixed 0-80 dB mapping: 14 % (issue 20)
    CHECK(distinct.size() >= 20);                    // not a binary mask
    REQUIRE(with_level > samples / 10);
    CHECK(double(level_at_0) < 0.5 * double(with_level));
    // The report says what the file holds.
    CHECK(report.total.samples == samples);
    CHECK(report.total.high == at_255);
    CHECK(report.total.low == level_at_0);
    CHECK(report.warning(path).empty());

    const auto sidecar = nlohmann::json::parse(file_bytes(path + ".json"));
    CHECK(sidecar["byte_mapping"]["lo_db"].get<double>() == report.mapping.lo_db);
    CHECK(sidecar["byte_mapping"]["hi_db"].get<double>() == report.mapping.hi_db);
    CHECK(sidecar["byte_mapping"]["chosen_by"] == "export.auto");
    CHECK(sidecar["clipped"]["at_255"].get<size_t>() == at_255);
    CHECK(sidecar["clipped"]["at_0_with_level"].get<size_t>() == level_at_0);
    CHECK(sidecar["clipped"]["at_255_fraction"].get<double>() == Approx(double(at_255) / double(samples)));
    REQUIRE(sidecar["frames"].size() == 2);
    CHECK(sidecar["frames"][1]["at_255"].get<size_t>() == report.frames[1].high);
}

TEST_CASE("the fixed 0-80 dB mapping saturates the shipwreck, and says so", "[exports][aris]") {
    const Wreck& w = wreck("exports_wreck_fixed");
    const std::string path = w.dir + "/fixed.aris";
    ExportParams fixed;
    fixed.auto_range = false; // lo_db 0, hi_db 80: the mapping before export.auto
    const ExportReport report =
        export_dataset(w.dir, path, dataset_container("--aris"), false, fixed, "--aris");
    CHECK_FALSE(report.mapping.automatic);
    CHECK(report.total.high_fraction() > 0.05);
    CHECK(report.warning(path).find("clipped at 255") != std::string::npos);
    size_t at_255 = 0;
    for (auto& f : read_aris(path, 48)) at_255 += size_t(std::count(f.samples.begin(), f.samples.end(), 255));
    CHECK(report.total.high == at_255);
}

TEST_CASE("an explicit byte mapping is honoured exactly in ARIS and MCAP", "[exports][aris][mcap]") {
    const std::string dir = batch_out("exports_explicit");
    const SceneDesc scene = small_aris_scene();
    prepare_dataset(dir, scene, line_trajectory("0.3,2.4,0.9,0.4,2.3,0.9,2", {-1, 30, -39}, 5, "test"));
    run_batch(dir, {});
    std::vector<PolarImage> images;
    for (size_t k = 0; k < 2; ++k)
        images.push_back(decode_npy(file_bytes(frame_prefix(dir, k) + ".npy"), "npy"));
    ExportParams p;
    p.auto_range = false, p.lo_db = 110, p.hi_db = 130;
    // The test's own reading of the mapping: 255 (L - lo) / (hi - lo), clamped, rounded; 0 without echo.
    auto expected = [&](float l) -> int {
        if (!std::isfinite(l)) return 0;
        const double t = std::min(1.0, std::max(0.0, (double(l) - 110) / 20));
        return int(std::floor(255 * t + 0.5));
    };
    const ExportReport a =
        export_dataset(dir, dir + "/x.aris", dataset_container("--aris"), false, p, "--aris");
    CHECK(a.mapping.lo_db == 110);
    CHECK(a.mapping.hi_db == 130);
    const auto frames = read_aris(dir + "/x.aris", 48);
    size_t mismatches = 0, middle = 0, at_255 = 0;
    for (size_t k = 0; k < 2; ++k)
        for (size_t i = 0; i < frames[k].samples.size(); ++i) {
            const int b = frames[k].samples[i];
            mismatches += b != expected(level_of(images[k], scene, frames[k], i));
            middle += b > 0 && b < 255;
            at_255 += b == 255;
        }
    CHECK(mismatches == 0);
    CHECK(middle > 100); // the mapping is exercised inside its range, not only at its ends
    CHECK(at_255 > 0);   // and at its top
    CHECK(a.total.high == at_255);

    // MCAP: the same bytes, range-major with beam 0 port-most; the mapping in the channel's metadata.
    const ExportReport m =
        export_dataset(dir, dir + "/x.mcap", dataset_container("--mcap"), false, p, "--mcap");
    // MCAP holds our bins (ARIS the device's samples): its counts are the images' own.
    size_t bins_255 = 0, bins_0 = 0;
    for (auto& img : images)
        for (float l : img.level_db)
            bins_255 += expected(l) == 255, bins_0 += std::isfinite(l) && expected(l) == 0;
    CHECK(m.total.high == bins_255);
    CHECK(m.total.low == bins_0);
    const auto bytes = file_bytes(dir + "/x.mcap");
    const std::string text(bytes.begin(), bytes.end());
    CHECK(text.find("byte_lo_db") != std::string::npos);
    const size_t hi = text.find("byte_hi_db");
    REQUIRE(hi != std::string::npos);
    CHECK(text.compare(hi + 10 + 4, 3, "130") == 0); // the map's value follows its uint32 length
    const auto sidecar = nlohmann::json::parse(file_bytes(dir + "/x.mcap.json"));
    CHECK(sidecar["byte_mapping"]["chosen_by"] == "export.lo_db, export.hi_db");
    CHECK(sidecar["byte_mapping"]["lo_db"].get<double>() == 110);
}

// Helpers of the dataset tests: a small fast scene, file bytes, fresh directories.
#pragma once
#include "core/data/polar_image.hpp"
#include "core/scene/params.hpp"
#include "core/scene/scene_io.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace sonarsim::test {

inline std::string batch_out(const std::string& name) {
    const std::string dir = std::string(SONARSIM_TEST_OUT) + "/batch/" + name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(std::filesystem::path(dir).parent_path());
    return dir;
}

/// A little-endian field of type T at byte `off` (the test host is little-endian, as the files are).
template <typename T> T at(const std::vector<std::uint8_t>& b, size_t off) {
    REQUIRE(off + sizeof(T) <= b.size());
    T v;
    std::memcpy(&v, b.data() + off, sizeof v);
    return v;
}

inline std::vector<std::uint8_t> file_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// The built-in scene, made small: 48 beams, 96 range bins, a coarse uniform grid of rays.
inline SceneDesc small_scene() {
    SceneDesc s = default_scene();
    for (const char* set :
         {"sonar.beams=48", "sonar.range_bins=96", "sampling.scheme=spread", "sampling.elevation_rays=41"})
        apply_setting_text(s, set, "test");
    validate_scene(s, "test");
    return s;
}

/// small_scene() as an ARIS file can hold it: 48 beams at 1200 kHz (the ARIS 1200 HF mode), from 1 m
/// (ARIS samples from SampleStartDelay 930 us, about 0.7 m), 256 bins of 15.6 mm (SamplePeriod 21 us, within
/// every system's; an ARIS frame holds at least 128 samples per beam).
inline SceneDesc small_aris_scene() {
    SceneDesc s = small_scene();
    for (const char* set : {"sonar.frequency_khz=1200", "sonar.range_min_m=1", "sonar.range_bins=256"})
        apply_setting_text(s, set, "test");
    validate_scene(s, "test");
    return s;
}

/// The test's own reading of an ARIS frame header field at `offset` (the vendor layout, little-endian).
template <typename T> T header_field(const std::vector<std::uint8_t>& header, size_t offset) {
    T v;
    std::memcpy(&v, header.data() + offset, sizeof v);
    return v;
}

/// The level of column `col` of `img` (bins spanning [range_min_m, range_max_m]) at range `r_m`, as ARIS
/// samples should hold it: the intensities 10^(L/10) of the two bins whose centres enclose r_m mixed in
/// proportion to the distances, the end bin's level outside the first and last centre; -inf without echo.
inline float level_at_range(const PolarImage& img, int col, double range_min_m, double range_max_m,
                            double r_m) {
    const double bin = (range_max_m - range_min_m) / img.bins;
    auto centre = [&](int i) { return range_min_m + (i + 0.5) * bin; };
    if (r_m <= centre(0)) return img.at(0, col);
    if (r_m >= centre(img.bins - 1)) return img.at(img.bins - 1, col);
    int lo = 0;
    while (centre(lo + 1) < r_m) ++lo;
    const double w = (r_m - centre(lo)) / bin;
    const double i =
        (1 - w) * std::pow(10.0, img.at(lo, col) / 10.0) + w * std::pow(10.0, img.at(lo + 1, col) / 10.0);
    return i > 0 ? float(10 * std::log10(i)) : -std::numeric_limits<float>::infinity();
}

} // namespace sonarsim::test

// Helpers of the dataset tests: a small fast scene, file bytes, fresh directories.
#pragma once
#include "core/scene/params.hpp"
#include "core/scene/scene_io.hpp"

#include <filesystem>
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
/// (ARIS samples from SampleStartDelay 930 us, about 0.7 m).
inline SceneDesc small_aris_scene() {
    SceneDesc s = small_scene();
    for (const char* set : {"sonar.frequency_khz=1200", "sonar.range_min_m=1"})
        apply_setting_text(s, set, "test");
    validate_scene(s, "test");
    return s;
}

} // namespace sonarsim::test

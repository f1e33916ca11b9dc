// Every fuzz seed and every input a fuzzer ever crashed on, through the fuzz targets' bodies.
#include "fuzz_targets.hpp"

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

namespace {

std::vector<std::filesystem::path> inputs(const std::string& target) {
    std::vector<std::filesystem::path> files;
    for (const char* set : {"corpus", "regressions"}) {
        const std::filesystem::path dir = std::filesystem::path(SONARSIM_FUZZ_DIR) / set / target;
        for (const auto& e : std::filesystem::directory_iterator(dir))
            if (e.is_regular_file() && e.path().filename().string()[0] != '.') files.push_back(e.path());
    }
    return files;
}

std::vector<std::uint8_t> bytes(const std::filesystem::path& p) {
    std::ifstream f(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

} // namespace

TEST_CASE("fuzz seeds and regressions: scene parser", "[input][fuzz]") {
    const auto files = inputs("scene");
    REQUIRE(files.size() >= 5);
    for (const auto& f : files) {
        INFO(f.string());
        const auto b = bytes(f);
        sonarsim::fuzz::scene_input(b.data(), b.size());
    }
}

TEST_CASE("fuzz seeds and regressions: mesh loading", "[input][fuzz]") {
    const auto files = inputs("mesh");
    REQUIRE(files.size() >= 4);
    for (const auto& f : files) {
        INFO(f.string());
        const auto b = bytes(f);
        sonarsim::fuzz::mesh_input(b.data(), b.size());
    }
}

TEST_CASE("fuzz seeds and regressions: ARIS reader", "[input][fuzz]") {
    const auto files = inputs("aris");
    REQUIRE(files.size() >= 4);
    for (const auto& f : files) {
        INFO(f.string());
        const auto b = bytes(f);
        sonarsim::fuzz::aris_input(b.data(), b.size());
    }
}

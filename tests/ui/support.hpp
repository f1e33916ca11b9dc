// Helpers of the viewer tests: output paths and whole-file reads.
#pragma once
#include <cstdint>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace sonarsim::test {

inline std::string ui_out_path(const std::string& name) {
    return std::string(SONARSIM_TEST_OUT) + "/" + name;
}

inline std::vector<std::uint8_t> read_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

} // namespace sonarsim::test

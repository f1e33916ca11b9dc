// libFuzzer target: ARIS recordings through the reader (core/io/aris_read) and the compare statistics.
// See docs/bad-input.md.
#include "fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    sonarsim::fuzz::aris_input(data, size);
    return 0;
}

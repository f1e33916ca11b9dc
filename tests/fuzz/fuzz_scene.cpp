// libFuzzer target: scene files, --set and --pose text (see docs/bad-input.md).
#include "fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    sonarsim::fuzz::scene_input(data, size);
    return 0;
}

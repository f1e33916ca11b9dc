// libFuzzer target: mesh files through load_mesh (OBJ, PLY, STL, OFF; the first byte picks).
// See docs/bad-input.md.
#include "fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    sonarsim::fuzz::mesh_input(data, size);
    return 0;
}

// The raw (polar) sonar image.
#pragma once
#include <cstddef>
#include <vector>

namespace sonarsim {

/// Raw (polar) image: rows = range bins (row 0 nearest), columns = beams (column 0 port-most).
struct PolarImage {
    int bins = 0, beams = 0;
    std::vector<float> level_db; ///< L_EN [dB]; -inf where nothing echoes. Index [bin * beams + beam].
    float at(int bin, int beam) const { return level_db[size_t(bin) * size_t(beams) + size_t(beam)]; }
};

} // namespace sonarsim

#include "core/display/polar_gray.hpp"

#include <cmath>

namespace sonarsim {

Image8 polar_gray_image(const PolarImage& img, const DisplayParams& d) {
    Image8 out;
    out.width = img.beams, out.height = img.bins, out.channels = 1;
    out.pixels.resize(size_t(img.beams) * img.bins);
    for (int b = 0; b < img.bins; ++b)
        for (int i = 0; i < img.beams; ++i)
            out.pixels[size_t(img.bins - 1 - b) * img.beams + i] =
                std::uint8_t(std::lround(gray_level(img.at(b, i), d.lo_db, d.hi_db)));
    return out;
}

} // namespace sonarsim

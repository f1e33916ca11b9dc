// PNG encoding of the 8-bit images sonarsim writes (fan, polar, plots, viewer screenshots).
#pragma once
#include "core/display/colormap.hpp"

#include <cstdint>
#include <vector>

namespace sonarsim {

using Bytes = std::vector<std::uint8_t>;

/// zlib compression level of encode_png: 3 writes the shipwreck's 1036 x 1000 fan in 14 ms at 89 kB (stb's
/// writer took 110 ms for 115 kB; zlib's level 6 takes 26 ms for 68 kB), a speckled device image in 30 ms.
constexpr int kPngDeflateLevel = 3;

/// A PNG (8 bits per channel; 1 channel gray, 3 RGB, 4 RGBA; not interlaced) of `image`, every row with the
/// Sub filter (each byte less the one a pixel to its left), compressed with zlib at kPngDeflateLevel.
/// Throws std::invalid_argument for an empty image, a channel count other than 1, 3 or 4, or pixels that do
/// not match width x height x channels.
Bytes encode_png(const Image8& image);

} // namespace sonarsim

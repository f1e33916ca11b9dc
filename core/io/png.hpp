// PNG encoding of the images sonarsim writes: 8-bit (fan, polar, plots, viewer screenshots) and 16-bit gray
// (the ground truth's maps).
#pragma once
#include "core/display/colormap.hpp"

#include <cstdint>
#include <string>
#include <utility>
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

/// A 16-bit gray PNG of `values` (row-major, width x height, row 0 at the top), filtered and compressed as
/// encode_png, with a tEXt chunk per (keyword, text) pair after the header (keywords of 1-79 Latin-1
/// characters; image tools show them, e.g. `identify -verbose`). Throws std::invalid_argument for an empty
/// image, a count that is not width x height, or a keyword or text that PNG does not allow.
Bytes encode_png_gray16(int width, int height, const std::vector<std::uint16_t>& values,
                        const std::vector<std::pair<std::string, std::string>>& text = {});

} // namespace sonarsim

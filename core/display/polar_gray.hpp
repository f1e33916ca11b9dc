// The raw (polar) image as gray: one pixel per (bin, beam).
#pragma once
#include "core/display/colormap.hpp"
#include "core/data/polar_image.hpp"

namespace sonarsim {

/// The raw image as gray: range grows upward (row 0 of the data at the bottom), beam 0 (port) on the left.
Image8 polar_gray_image(const PolarImage& img, const DisplayParams& display);

} // namespace sonarsim

// Non-GL helpers for the sonar image panel: the raw polar image in colour, tick steps, and one beam's
// echo levels (A-scan).
#pragma once
#include "core/image.hpp"
#include "core/shade.hpp"

#include <vector>

namespace sonarsim::ui {

/// The raw image in the display's colour map: width = beams (beam 0 left), height = bins (far range on
/// top), like polar_gray_image but RGB.
Image8 polar_color_image(const PolarImage& image, const DisplayParams& display);

/// A "nice" tick step (1, 2 or 5 x 10^k) giving about `count` ticks over `span`.
double nice_step(double span, int count);

/// L_EN [dB] of one beam against range bin (-inf where nothing echoes); empty for a bad beam.
std::vector<float> beam_levels(const PolarImage& image, int beam);

/// The beam holding the highest echo level (the middle beam when nothing echoes).
int strongest_beam(const PolarImage& image);

} // namespace sonarsim::ui

// Non-GL helpers for the sonar image panel: the raw polar image in colour, tick steps, and one beam's
// echo levels (A-scan).
#pragma once
#include "core/display/image.hpp"
#include "core/pipeline/simulator.hpp"
#include "core/shading/shade.hpp"

#include <cstdint>
#include <memory>
#include <vector>

namespace sonarsim::ui {

/// The raw image in the display's colour map: width = beams (beam 0 left), height = bins (far range on
/// top), like polar_gray_image but RGB; cells where nothing echoes in no_echo_rgb. The gray level is rounded
/// to one of 256 before the colour map, as in the fan.
Image8 polar_color_image(const PolarImage& image, const DisplayParams& display);

/// The frame's fan (sector image) with the pixels whose nearest sample has no echo painted in no_echo_rgb,
/// through the taps the fan was formed with (Frame::sector_map_ptr): no per-pixel geometry here. Throws
/// std::invalid_argument for a frame without them (every frame a Simulator makes has them).
Image8 fan_with_no_echo(const Frame& frame, Colormap map);

/// A "nice" tick step (1, 2 or 5 x 10^k) giving about `count` ticks over `span`.
double nice_step(double span, int count);

/// L_EN [dB] of one beam against range bin (-inf where nothing echoes); empty for a bad beam.
std::vector<float> beam_levels(const PolarImage& image, int beam);

/// The beam whose azimuth sector holds `azimuth_deg` (the nearest beam outside the field of view): where the
/// A-scan stays when the beam count changes.
int beam_at_azimuth(double azimuth_deg, const SonarGrid& grid);

/// The beam holding the highest echo level (the middle beam when nothing echoes).
int strongest_beam(const PolarImage& image);

} // namespace sonarsim::ui

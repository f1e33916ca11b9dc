// Display levels: an 8-bit image, the gray level of an L_EN and the colour maps.
#pragma once
#include "core/data/scene.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace sonarsim {

struct Image8 {
    int width = 0, height = 0, channels = 0;
    std::vector<std::uint8_t> pixels; ///< row-major, top row first
};

/// gray = 255 clamp((L_EN - lo) / (hi - lo), 0, 1); -inf maps to 0. Returned as a float in [0, 255].
float gray_level(float level_db, double lo_db, double hi_db);

/// RGB of a colour map at t in [0, 1].
std::array<std::uint8_t, 3> colormap_rgb(Colormap map, double t);
/// The map's 256 display colours: entry g is colormap_rgb(map, g / 255), for a gray level rounded to g.
std::array<std::array<std::uint8_t, 3>, 256> colormap_table(Colormap map);
/// The colour a viewer shows for cells where nothing echoes (L_EN = -inf), distinct from the map's low end.
std::array<std::uint8_t, 3> no_echo_rgb(Colormap map);

} // namespace sonarsim

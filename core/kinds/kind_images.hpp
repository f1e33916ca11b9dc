// The images a side-scan's and a scanning sonar's users know, formed from the traced pings: the waterfall
// (port mirrored on the left, starboard on the right, newest ping at the top; slant or ground range) and the
// sweep (the head's pings around the sonar, forward up, port on the left).
#pragma once
#include "core/display/colormap.hpp"
#include "core/data/polar_image.hpp"
#include "core/kinds/ping_series.hpp"

namespace sonarsim {

/// The waterfall's levels [dB]: one row per ping (row 0 the first), 2 x bins columns: port from far (column
/// 0) to near, then starboard from near to far. Slant range: the bins as heard. Ground range: column j of
/// each side at ground range (j + 1/2) r_max / bins, read at slant range sqrt(g^2 + h^2) (linear in dB
/// between bins) with h the ping's first bottom return; -inf beyond r_max, before r_min and where a ping has
/// no bottom return. As a PolarImage: bins = pings, beams = columns.
PolarImage waterfall_levels(const PingSeries& series, SidescanRange range, double range_max_m);

/// The waterfall as RGB: newest ping at the top; `display` maps levels to the colour map.
Image8 waterfall_image(const PolarImage& waterfall, const DisplayParams& display);

/// A scan's raw array [dB]: one row per step (row 0 the first), one column per bin.
PolarImage scan_levels(const PingSeries& series);

/// The sweep as RGB, `size_px` square: the sonar at the centre, its forward axis up, port on the left, r_max
/// at the edge; each pixel the bin of its range in the step of its head angle (within half a step), the
/// colour map's no-echo colour outside the swept sector and beyond r_max.
Image8 sweep_image(const PingSeries& series, const DisplayParams& display, double range_max_m, int size_px);

} // namespace sonarsim

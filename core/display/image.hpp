// The display stage: colour maps, the display range, the raw (polar) image and the fan.
#pragma once
#include "core/display/colormap.hpp"
#include "core/display/display_range.hpp"
#include "core/display/polar_gray.hpp"
#include "core/display/sector.hpp"

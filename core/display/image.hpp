// The display stage: colour maps, the display range, the raw (polar) image and the fan.
#pragma once
#include "core/display/sector.hpp"

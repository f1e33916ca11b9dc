// Shading: apply the sonar equation to stored hits and sum echoes in linear intensity per (range bin, beam).
#pragma once
#include "physics.hpp"
#include "polar_image.hpp"
#include "scene.hpp"
#include "trace.hpp"

#include <vector>

namespace sonarsim {

/// Material of index `m` (kFloorMaterial or object index + 1).
const Material& material_of(const SceneDesc& scene, unsigned m);

/// Fraction of a cell's echo that falls in [r0, r1): "uniform" puts all of it in the bin of its range;
/// "spread" distributes it over the cell's range footprint (sum of its elevation and azimuth extents).
double cell_fraction_in(const Cell& cell, SamplingScheme scheme, double r0, double r1);

/// L_EN image of the stored hits. Accumulates per bin in the log domain (running max + scaled sum), so
/// intensities far below double's range (high absorption, grazing q) neither underflow nor overflow.
PolarImage shade(const TraceResult& hits, const SceneDesc& scene);

} // namespace sonarsim

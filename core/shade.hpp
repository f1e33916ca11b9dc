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

/// What the sensor stage needs from the cells beyond the image (computed only when it needs it).
struct SensorInputs {
    int sub = 1;     ///< fine azimuth columns per beam (column j = beam * sub + s, s = 0 port-most)
    PolarImage fine; ///< L_EN [dB] per (range bin, fine column) when sub > 1; otherwise empty
    /// Per (range bin, beam) [bin * beams + beam]: the echo-weighted mean elevation [rad] of what echoes
    /// there (each cell at the elevation where its footprint crosses the bin's centre range); NaN where
    /// nothing echoes. Empty unless speckle is on (it anchors the speckle to the scatterers).
    std::vector<float> elevation_rad;
};

/// True when the sensor needs SensorInputs: a receive pattern finer than the beams, or speckle.
bool needs_sensor_inputs(const SceneDesc& scene);

/// The sensor's inputs, from the same cells and footprints as shade().
SensorInputs shade_sensor_inputs(const TraceResult& hits, const SceneDesc& scene);

/// Each cell's echo level before noise in natural-log units (cell_echo_db times ln 10 / 10; -inf where
/// nothing returns) into x; returns the largest (-inf when none).
double cell_levels(const std::vector<Cell>& cells, const SceneDesc& scene, const ShadeConstants& k,
                   std::vector<double>& x);

/// L_EN image of the stored hits. Accumulates per bin in the log domain (running max + scaled sum), so
/// intensities far below double's range (high absorption, grazing q) neither underflow nor overflow.
PolarImage shade(const TraceResult& hits, const SceneDesc& scene);

} // namespace sonarsim

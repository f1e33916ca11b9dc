// The sensor's effects that act on one range bin at a time (a row: every beam's linear intensity), in the
// order they are applied once the field is formed (sensor.cpp) and before TVG and gain: the beam table's
// relative response, the K distribution's texture, noise. Each is its own file: its maker reads the scene
// once per image and returns null when the scene leaves the effect off; apply() then changes rows in place.
#pragma once
#include "core/data/scene.hpp"
#include "core/grid/sonar_grid.hpp"
#include "core/shading/accumulate.hpp"

#include <memory>
#include <vector>

namespace sonarsim {

/// What every row effect may read about the image being formed.
struct RowContext {
    const SceneDesc& scene;
    const SonarGrid& grid;
    const SensorInputs* inputs; ///< null when the scene needs none (needs_sensor_inputs)
    double peak_db;             ///< the level the rows' intensities are relative to (10^(peak_db / 10) = 1)
    bool speckle;               ///< the field was formed with speckle (speckle_field.hpp)
};

class RowEffect {
  public:
    virtual ~RowEffect() = default;
    /// Row `bin` (centre range range_m) of grid.beams linear intensities, changed in place. Called from
    /// several threads at once, each on its own row.
    virtual void apply(int bin, double range_m, double* row) const = 0;
};

struct RowEffectEntry {
    const char* name;
    std::unique_ptr<const RowEffect> (*make)(const RowContext& context); ///< null when off
};

/// The row effects in the order they apply.
const std::vector<RowEffectEntry>& row_effects();

} // namespace sonarsim

// Shading: the sonar equation on each stored contribution (a cell, or a multipath ghost). The pass that sums
// them per (range bin, beam) is accumulate.hpp.
#pragma once
#include "core/shading/physics.hpp"
#include "core/shading/texture.hpp"
#include "core/data/scene.hpp"
#include "core/data/hits.hpp"

#include <vector>

namespace sonarsim {

/// Material of index `m` (kFloorMaterial, kSurfaceMaterial or object index + 1). Inline: shading and the
/// sampler's criteria ask for it once or more per cell.
inline const Material& material_of(const SceneDesc& s, unsigned m) {
    static const Material none{};
    if (m == kFloorMaterial) return s.seafloor ? s.seafloor->material : none;
    if (m == kSurfaceMaterial) return s.water.surface_material;
    return s.objects.at(m - 1).material;
}

/// Fraction of a cell's echo that falls in [r0, r1): "point" binning puts all of it in the bin of its range;
/// "footprint" distributes it over the cell's range footprint (sum of its elevation and azimuth extents).
double cell_fraction_in(const Cell& cell, EchoBinning binning, double r0, double r1);

/// One reflection's 10 log10 |R|^2 [dB] on mirror `material` at incidence cos_incidence: the water surface's
/// coherent reflection 10 log10 exp(-(2 k sigma cos)^2) (Kirchhoff/Eckart: amplitude exp(-2 k^2 sigma^2
/// cos^2); pressure release, |R0| = 1), or -reflection_db.
double reflection_gain_db(const ShadeConstants& k, const SceneDesc& scene, unsigned material,
                          double cos_incidence);

/// Echo level of a multipath ghost before noise [dB]: L_S - 2 alpha r - 20 log10(other leg) +
/// 10 log10(dOmega / cos) + L_BS + the 10 log10 |R|^2 of each reflection (the mirrors twice on double paths).
/// Spreading and absorption take the whole path (r is half of it); the area is the area leg's. L_BS is the
/// monostatic GSAB on double paths, Lambert's bistatic nu cos^{q/2} theta_in cos^{q/2} theta_out on mixed
/// ones (no specular term). Reduces to cell_echo_db for a double path without mirrors.
double ghost_echo_db(const ShadeConstants& k, const SceneDesc& scene, const GhostCell& ghost);

/// The contributions to one beam: its cells, then the ghosts arriving in it (none without multipath).
class BeamContributions {
  public:
    BeamContributions(const TraceResult& hits, int beam);
    size_t size() const { return cells_.size() + (ghosts_ ? ghosts_->size() : 0); }
    const Cell& operator[](size_t n) const {
        return n < cells_.size() ? cells_[n] : (*ghosts_)[n - cells_.size()].cell;
    }
    /// The ghost behind contribution n; nullptr for a direct cell.
    const GhostCell* ghost(size_t n) const {
        return n < cells_.size() ? nullptr : &(*ghosts_)[n - cells_.size()];
    }

  private:
    const std::vector<Cell>& cells_;
    const std::vector<GhostCell>* ghosts_ = nullptr;
};

/// Each contribution's echo level before noise in natural-log units (cell_echo_db or ghost_echo_db times
/// ln 10 / 10; -inf where nothing returns) into x; returns the largest (-inf when none). With `texture`
/// (null when no material has one), each level gains its material's texture at the contribution's point, and
/// a direct cell's backscatter takes the facet's tilted incidence (its area stays the mean plane's).
double contribution_levels(const BeamContributions& beam, const SceneDesc& scene, const ShadeConstants& k,
                           std::vector<double>& x, const SceneTexture* texture = nullptr);

} // namespace sonarsim

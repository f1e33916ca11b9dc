// Multipath by the image-source method, internal to the tracers (trace.cpp, adaptive.cpp). From a ray's
// first hit on a mirror (the water surface, or a material with reflection_db) the specular continuation is
// traced, up to sampling.bounces reflections. Each scatterer it meets echoes back along the mirrored path
// (a double path: monostatic backscatter seen from the image sonar) and, where it sees the sonar directly,
// along the two mixed paths (one leg by the mirrors, one direct). See core/ARCHITECTURE.md, "Multipath".
#pragma once
#include "trace_detail.hpp"

#include <cstdint>
#include <vector>

namespace sonarsim::detail {

/// True when the scene has paths to follow: sampling.bounces > 0 and a mirror in it.
bool multipath_active(const SceneDesc& scene);

/// Finds the ghosts of single rays.
class Multipath {
  public:
    Multipath(const SceneGeometry& geometry, const SceneDesc& scene, const RayFrame& frame);
    /// Appends the ghosts of the ray (a, e) standing for the cell [a_lo, a_hi] x [e_lo, e_hi] whose first
    /// hit is `h` (each with the beam it arrives in) to `out`; returns the rays it traced.
    std::uint64_t ghosts(const Hit& h, const Angle& a, const Angle& e, const Angle& a_lo, const Angle& a_hi,
                         const Angle& e_lo, const Angle& e_hi, std::vector<GhostCell>& out) const;

  private:
    std::uint64_t emit(const RayFrame& image, const Hit& hit, int k, const GhostCell& chain, const Angle& a,
                       const Angle& e, const Angle& a_lo, const Angle& a_hi, const Angle& e_lo,
                       const Angle& e_hi, std::vector<GhostCell>& out) const;
    int beam_of(double azimuth_rad) const;
    bool is_mirror(unsigned material) const;

    const SceneGeometry& g_;
    const SceneDesc& s_;
    const RayFrame& f_;
    double half_azimuth_rad_, half_elevation_rad_, beam_rad_;
};

/// Moves ghosts collected per source beam to the beams they arrive in, in a fixed order (source beam, then
/// as produced), so that the result does not depend on threading.
std::vector<std::vector<GhostCell>> gather_ghosts(std::vector<std::vector<GhostCell>>& by_source, int beams);

} // namespace sonarsim::detail

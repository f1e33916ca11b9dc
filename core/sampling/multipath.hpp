// Multipath by the image-source method, internal to the tracers (trace.cpp, adaptive.cpp). From a ray's
// first hit on a mirror (the water surface, or a material with reflection_db) the specular continuation is
// traced, up to sampling.bounces reflections. Each scatterer it meets echoes back along the mirrored path
// (a double path: monostatic backscatter seen from the image sonar) and, where it sees the sonar directly,
// along the two mixed paths (one leg by the mirrors, one direct). See core/sampling/README.md, "Multipath".
#pragma once
#include "core/sampling/trace_detail.hpp"
#include "core/shading/physics.hpp"

#include <atomic>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

namespace sonarsim::detail {

/// True when the scene has paths to follow: sampling.bounces > 0 and a mirror in it.
bool multipath_active(const SceneDesc& scene);

/// A ghost whose whole echo lies this far below what the tolerance allows each bin of its footprint
/// (sampling.tolerance_db's relative error per bin, over kErrorsPerBin, times the direct echo there) is
/// culled before its shadow ray and its shading: 1/8 of that allowance (with tolerance_db 0.1: ghosts
/// 30 dB under the direct echo of every bin they touch).
constexpr double kGhostCullShare = 1.0 / 8;

/// The direct echo ghosts are culled against: per beam and range bin [dB, as cell_echo_db; -inf: none],
/// [beam * bins + bin]; and how far below it a ghost's echo must lie to be culled [dB, negative].
struct GhostCullFloor {
    const std::vector<float>* echo_db = nullptr; ///< null or empty: no culling
    double margin_db = -INFINITY;
    /// The floor is taken as its least value over the ghost's bins widened by this many bins and beams
    /// each way (an estimate of the direct echo may misplace it by that much).
    int margin_bins = 0, margin_beams = 0;
};

/// Finds the ghosts of single rays.
class Multipath {
  public:
    Multipath(const SceneGeometry& geometry, const SceneDesc& scene, const RayFrame& frame);

    /// Culls ghosts against `floor` from now on (the adaptive sampler's base image; default: none).
    void set_cull_floor(const GhostCullFloor& floor) { cull_ = floor; }
    /// Ghosts culled so far (by every thread).
    std::uint64_t culled() const { return culled_.load(std::memory_order_relaxed); }
    /// The first reflection of the ray (a, e) whose first hit is `h`: what its specular continuation meets
    /// (t: the whole path length from the sonar; nullopt when it meets nothing within reach), or nothing
    /// (`reflected` false) when `h` is no mirror.
    struct Continuation {
        bool reflected = false;
        std::optional<Hit> hit;
        double cos_at_hit = 0; ///< incidence at what the continuation meets
        /// Whether the direct leg from what it meets back to the sonar is blocked (-1: not traced yet).
        /// A cell and the coarser cell around it (the error estimate's) share the ray and this shadow ray.
        mutable std::int8_t direct_leg_blocked = -1;
    };
    Continuation continuation(const Hit& h, const Angle& a, const Angle& e) const;

    /// Appends the ghosts of the ray (a, e) standing for the cell [a_lo, a_hi] x [e_lo, e_hi] whose first
    /// hit is `h` (each with the beam it arrives in) to `out`; returns the rays it traced. `beam`: the beam
    /// whose slice holds azimuth a (the ray's own). `first`: the ray's continuation() when already traced.
    std::uint64_t ghosts(const Hit& h, const Angle& a, const Angle& e, const Angle& a_lo, const Angle& a_hi,
                         const Angle& e_lo, const Angle& e_hi, int beam, std::vector<GhostCell>& out,
                         const Continuation* first = nullptr) const;

  private:
    /// `ray_beam`: the ray's beam (ghosts()). `blocked`: the cached shadow ray of this scatterer (null: none
    /// to share).
    std::uint64_t emit(const RayFrame& image, const Hit& hit, int k, const GhostCell& chain, const Angle& a,
                       const Angle& e, const Angle& a_lo, const Angle& a_hi, const Angle& e_lo,
                       const Angle& e_hi, int ray_beam, std::vector<GhostCell>& out,
                       std::int8_t* blocked) const;
    int beam_of(double azimuth_rad) const;
    bool is_mirror(unsigned material) const;
    /// What the reflected ray from mirror point x along d2 meets, its t the whole path length (`travelled`
    /// so far, plus the rest); within twice the window's reach (a mixed path's other leg is direct and
    /// shorter).
    std::optional<Hit> trace_on(const glm::dvec3& x, const glm::dvec3& d2, double travelled) const;
    /// Reflects `image` (the sonar mirrored so far) in the mirror `hit` of its ray (a, e): returns the
    /// mirror point and sets d2, the reflected direction.
    glm::dvec3 reflect(RayFrame& image, const Hit& hit, const Angle& a, const Angle& e, glm::dvec3& d2) const;

    /// Whether ghost g, arriving in beams [beam_lo, beam_hi] over ranges [r_lo, r_hi], lies below the cull
    /// floor in every bin it touches.
    bool negligible(const GhostCell& g, int beam_lo, int beam_hi, double r_lo_m, double r_hi_m) const;

    const SceneGeometry& g_;
    const SceneDesc& s_;
    const RayFrame& f_;
    /// f_ without its grid, copied for each ray as the frame of its image sonars: copying the grid's
    /// shared_ptr would have every thread write its count, one cache line they all contend for.
    RayFrame image_start_;
    ShadeConstants k_;
    double half_azimuth_rad_, half_elevation_rad_;
    GhostCullFloor cull_;
    mutable std::atomic<std::uint64_t> culled_{0};
};

/// Moves ghosts collected per source (list k: found by the rays of one beam, or of one sample beam) to the
/// beams they arrive in, in a fixed order so that the result does not depend on threading: beam i's list
/// is list i's ghosts that arrive wholly in beam i (most: they stay where they are), as produced, then the
/// others arriving in it, by source and as produced.
/// A ghost arriving over several beams' azimuths is shared among them by the part of its interval in each.
std::vector<std::vector<GhostCell>> gather_ghosts(std::vector<std::vector<GhostCell>>& by_source,
                                                  const SceneDesc& scene);
/// The same with each source's ghosts already split as they were made: `by_source[k]` only those that
/// arrive wholly in beam k (stays_in_source), `away[k]` the others, each as produced. Saves moving the
/// staying ones (most) out of the way of the others.
std::vector<std::vector<GhostCell>> gather_ghosts(std::vector<std::vector<GhostCell>>& by_source,
                                                  std::vector<std::vector<GhostCell>>& away,
                                                  const SceneDesc& scene);

/// Whether ghost g, found by the rays of source `source` (gather_ghosts), arrives wholly in beam `source`:
/// it stays in that source's list.
bool stays_in_source(const GhostCell& g, std::size_t source, const SonarGrid& grid);

} // namespace sonarsim::detail

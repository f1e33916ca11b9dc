// Work-precision measurement: render a scene with a sampling setting, time it, and measure its error.
#pragma once
#include "core/geometry/geometry.hpp"
#include "core/analysis/reference.hpp"
#include "core/scene/sampling_scheme.hpp"
#include "core/data/scene.hpp"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace sonarsim {

struct Sampling {
    SamplingScheme scheme;
    int elevation_rays, azimuth_rays;
    std::string label() const;
};

struct StudyRow {
    Sampling sampling;
    double time_ms = 0; ///< median over repeats of trace + shade (the raw image)
    double rays = 0;    ///< rays traced for one image
    ImageError error;
    TraceResult::ErrorEstimate estimate; ///< the adaptive scheme's own estimate
};

/// Called with the fraction of the work done so far, in [0, 1].
using Progress = std::function<void(double fraction)>;

/// The reference a study measures against, and how converged it is.
struct StudyReference {
    PolarImage image;
    std::string kind;        ///< "semi-analytic floor integral" or "dense spread run, streamed"
    std::string description; ///< its settings
    ImageError convergence;  ///< the reference against a coarser version of itself
    double time_ms = 0;
    std::uint64_t rays = 0; ///< rays traced for the reference image (0 for the floor integral)
};

/// Dense sampling of the non-floor reference. Rel L1 against 6561 x 81 rays per beam: on the Fig. 9 scene,
/// where edges cutting a beam in azimuth dominate, 6561 x 9: 3e-4, 2187 x 27: 6e-5, 6561 x 27: 6e-5; on the
/// shipwreck, where elevation dominates, 2187 x 27: 5e-4, 2187 x 81: 4e-4, 6561 x 27: 9e-5. The convergence a
/// study reports (the run 3x coarser against it) overstates the reference's own error several times: on the
/// shipwreck, 2187 x 9 differs from it by ~1e-3.
constexpr Sampling kReferenceSampling{SamplingScheme::Spread, 6561, 27};

/// Cells (one per ray that hits) a streamed render keeps in memory at once, about 48 bytes each.
constexpr std::size_t kChunkCells = std::size_t(1) << 20;

/// A bare flat floor: the semi-analytic integral. Otherwise a dense `spread` run (`dense`, true normals)
/// traced and shaded a chunk of beams at a time, so its memory stays bounded whatever the scene; its
/// convergence is measured against a run 3x coarser in both directions.
StudyReference make_reference(const SceneGeometry& g, const SceneDesc& scene, const Progress& progress = {},
                              const Sampling& dense = kReferenceSampling);

/// The scene restricted to beams [first_beam, last_beam) of `scene`: same position, a fan of
/// last_beam - first_beam beams whose azimuths are exactly those beams' azimuths (its fov is
/// Theta (last - first) / N, its orientation R Rz(a_c), a_c the chunk's centre azimuth).
SceneDesc beam_subscene(const SceneDesc& scene, int first_beam, int last_beam);

/// Roll, pitch, yaw [deg] of a rotation matrix, R = Rz(yaw) Ry(pitch) Rx(roll) (inverse of
/// rotation_matrix). At pitch +-90 deg, where only yaw -+ roll is defined, yaw is whatever atan2 of two
/// rounding residues gives.
Vec3d orientation_deg_of(const glm::dmat3& R);

/// Renders `scene` with a `uniform` or `spread` sampling, `beams_per_chunk` beams at a time (0: as many as
/// keep about kChunkCells cells in memory): only one chunk's cells live at once. Equals trace + shade of the
/// whole scene (up to rounding). `rays` (optional) receives the rays traced.
PolarImage render_in_chunks(const SceneGeometry& g, const SceneDesc& scene, const Sampling& sampling,
                            int beams_per_chunk = 0, const Progress& progress = {},
                            std::uint64_t* rays = nullptr);

/// Renders `scene` with `sampling` `repeats` times; time is the median of trace + shade.
StudyRow measure(const SceneGeometry& g, const SceneDesc& scene, const Sampling& sampling, int repeats,
                 const PolarImage& reference);

/// The default ladder: uniform from the paper's 281 rays up to dense, spread and adaptive from coarse up.
std::vector<Sampling> default_ladder(bool quick);

} // namespace sonarsim

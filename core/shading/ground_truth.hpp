// Ground truth per (range bin, beam): what echoed into each cell of the raw image, from the same cells and
// footprints as the image itself (footprint.hpp), so it converges with the sampler. Computed only when asked
// for (render --ground-truth, batch --ground-truth, the Python module, the viewer's snapshot toggle).
#pragma once
#include "core/data/scene.hpp"
#include "core/data/hits.hpp"

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace sonarsim {

/// Arrays of the raw image's shape (range_bins, beams), row 0 nearest; point_m has a last axis of 3.
/// Each contribution is a cell's echo in the bin (as shaded) at the elevation where its surface crosses the
/// bin's centre range; NaN (object_id -1, surfaces 0) where nothing echoes. A multipath ghost counts where it
/// arrives (its elevation is the arrival direction's); its point is the scatterer's, not the apparent one.
struct GroundTruth {
    int bins = 0, beams = 0;
    std::vector<float> elevation_deg;     ///< echo-weighted mean elevation [deg]
    std::vector<float> elevation_min_deg; ///< lowest elevation echoing into the cell [deg]: the ambiguity
    std::vector<float> elevation_max_deg; ///< highest [deg]
    std::vector<float> point_m;           ///< echo-weighted centroid, world coordinates [m], x y z per cell
    /// echo-weighted mean distance from the sonar to what echoes [m]: the bin's centre range for direct
    /// echoes; a multipath ghost's is its scatterer's, nearer than where it shows
    std::vector<float> range_m;
    /// Strongest contribution: -1 nothing, 0 seafloor, i + 1 objects[i], -2 the water surface.
    std::vector<std::int32_t> object_id;
    std::vector<float> incidence_deg;   ///< echo-weighted mean incidence angle [deg]
    std::vector<std::int32_t> surfaces; ///< distinct surfaces contributing (the floor and each object once)
    /// Specular reflections (out and back) on the strongest contribution's path: 0 direct, > 0 a ghost.
    std::vector<std::int32_t> bounces;
};

/// One array of the ground truth: its name (the file PREFIX_gt_NAME.npy, the Python module's key), its
/// member (float32 or int32), values per cell and the value of a cell where nothing echoes.
struct GroundTruthField {
    const char* name;
    std::vector<float> GroundTruth::*f32;        ///< a float32 array, or null
    std::vector<std::int32_t> GroundTruth::*i32; ///< an int32 array, or null
    int components;                              ///< values per cell: 3 for point_m (x y z), else 1
    float empty;                                 ///< where nothing echoes: NaN, -1 (object_id) or 0
};

/// The arrays in file order: elevation_deg, elevation_min_deg, elevation_max_deg, point_m, range_m,
/// object_id, incidence_deg, surfaces, bounces.
const std::vector<GroundTruthField>& ground_truth_fields();

/// Ground truth of the stored hits alone (accumulate() with the ground-truth channel); a Simulator asked for
/// it (Simulator::request) makes it in the same pass as the image.
GroundTruth compute_ground_truth(const TraceResult& hits, const SceneDesc& scene);

/// Arrays of the given shape, each cell as where nothing echoes.
GroundTruth empty_ground_truth(int bins, int beams);

/// The path of a contribution to beam `beam` (index in BeamContributions order, e.g. the strongest one of an
/// image cell from accumulate()'s strongest channel), for drawing: world points from the sonar out to the
/// scatterer and back (sonar, mirrors out, scatterer, mirrors back, sonar); no points for index -1.
struct EchoPath {
    std::vector<std::array<double, 3>> points_m;
    int bounces = 0;             ///< reflections out and back
    int out_bounces = 0;         ///< those on the way out: points_m[1 + out_bounces] is the scatterer
    std::int32_t object_id = -1; ///< the scatterer, as GroundTruth::object_id
};
EchoPath echo_path(const TraceResult& hits, const SceneDesc& scene, int beam, std::int32_t contribution);

/// The names of the arrays (ground_truth_fields), in file order.
const std::vector<std::string>& ground_truth_names();

} // namespace sonarsim

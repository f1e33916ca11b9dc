// Independent answers to compare sampling schemes against (sonarsim study, tests).
#pragma once
#include "core/data/scene.hpp"
#include "core/data/polar_image.hpp"
#include "core/shading/shade.hpp"

namespace sonarsim {

/// True when the scene is a bare flat floor (no objects), for which floor_reference() applies.
bool has_floor_reference(const SceneDesc& scene);

/// Semi-analytic L_EN image of a bare flat floor (SONAR_MODEL.md "What one pixel holds"): for each azimuth
/// node of a composite Gauss-Legendre rule across the beam, the elevation integral is split at the
/// closed-form roots of r(e) = bin edge and each piece integrated with Gauss-Legendre. `azimuth_panels` x 8
/// nodes per beam.
PolarImage floor_reference(const SceneDesc& scene, int azimuth_panels = 16);

/// Error of an image against a reference (both L_EN in dB).
struct ImageError {
    double rel_l1 = 0;        ///< sum |E - E_ref| / sum E_ref, linear intensity
    double median_abs_db = 0; ///< median |dB difference| over bins echoing in both
    double p95_abs_db = 0;    ///< 95th percentile of the same
    long holes = 0;           ///< bins echoing in the reference but empty in the image
    long spurious = 0;        ///< bins empty in the reference but echoing in the image
    long echoing_ref = 0;     ///< bins echoing in the reference
};
ImageError compare_images(const PolarImage& image, const PolarImage& reference);

} // namespace sonarsim

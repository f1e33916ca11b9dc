// Work-precision measurement: render a scene with a sampling setting, time it, and measure its error.
#pragma once
#include "geometry.hpp"
#include "reference.hpp"
#include "scene.hpp"

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

/// The reference a study measures against, and how converged it is.
struct StudyReference {
    PolarImage image;
    std::string kind;        ///< "semi-analytic floor integral" or "dense adaptive run"
    std::string description; ///< its settings
    ImageError convergence;  ///< the reference against a coarser version of itself
    double time_ms = 0;
};

StudyReference make_reference(const SceneGeometry& g, const SceneDesc& scene);

/// Renders `scene` with `sampling` `repeats` times; time is the median of trace + shade.
StudyRow measure(const SceneGeometry& g, const SceneDesc& scene, const Sampling& sampling, int repeats,
                 const PolarImage& reference);

/// The default ladder: uniform from the paper's 281 rays up to dense, spread and adaptive from coarse up.
std::vector<Sampling> default_ladder(bool quick);

} // namespace sonarsim

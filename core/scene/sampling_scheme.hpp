// The ray placements and the sampling schemes (names for the combinations of ray placement and echo
// binning, sampling.scheme): the one list of each, for the parameter table, validation, invalidation, the
// study and the benchmarks. A placement's tracer is its case in trace() (sampling/trace.cpp).
#pragma once
#include "core/data/scene.hpp"

#include <array>
#include <optional>

namespace sonarsim {

/// What the rest of the program needs to know of a ray placement.
struct PlacementSpec {
    RayPlacement placement;
    const char* name;
    const char* help;           ///< for sampling.placement's description
    const char* binning_reason; ///< why it needs footprint binning (null: it takes point binning too)
    bool regular_grid;          ///< a regular ray grid, on which "paper" normals (neighbour differences) work
    bool placed_by_shading;     ///< where its rays go depends on shading values (their rows then re-place)
    bool chunks;                ///< its beams can be traced a chunk at a time (a beam needs no neighbour)
};

/// In RayPlacement order.
inline constexpr std::array<PlacementSpec, 3> kRayPlacements = {{
    {RayPlacement::Grid, "grid", "elevation_rays x azimuth_rays per beam", nullptr, true, false, true},
    {RayPlacement::Adaptive, "adaptive",
     "that grid refined until sampling.tolerance_db and tolerance_rel_l1 are met",
     "its refinement and error estimate assume each cell's echo spread over its range footprint", false, true,
     false},
    {RayPlacement::Jittered, "jittered",
     "that many strata of four rays, two independent antithetic pairs at seeded random points, whose "
     "difference estimates the image's error (no refinement)",
     "its error estimate measures the footprint's bias", false, false, true},
}};

inline const PlacementSpec& placement_spec(RayPlacement p) {
    return kRayPlacements[size_t(p)];
}

struct NamedSampling {
    SamplingScheme scheme;
    const char* name;
    RayPlacement placement;
    EchoBinning binning;
};

/// In SamplingScheme order. A placement that needs footprint binning has no name with point binning: the
/// combination is rejected (validate_scene).
inline constexpr std::array<NamedSampling, 4> kSamplingSchemes = {{
    {SamplingScheme::Uniform, "uniform", RayPlacement::Grid, EchoBinning::Point},
    {SamplingScheme::Spread, "spread", RayPlacement::Grid, EchoBinning::Footprint},
    {SamplingScheme::Adaptive, "adaptive", RayPlacement::Adaptive, EchoBinning::Footprint},
    {SamplingScheme::Jittered, "jittered", RayPlacement::Jittered, EchoBinning::Footprint},
}};

inline const char* scheme_name(SamplingScheme s) {
    return kSamplingSchemes[size_t(s)].name;
}

/// The scheme whose combination the sampling settings are; none for adaptive placement with point binning.
inline std::optional<SamplingScheme> scheme_of(const SamplingParams& p) {
    for (const auto& n : kSamplingSchemes)
        if (n.placement == p.placement && n.binning == p.binning) return n.scheme;
    return std::nullopt;
}

/// Sets placement and binning to the scheme's combination.
inline void set_scheme(SamplingParams& p, SamplingScheme s) {
    p.placement = kSamplingSchemes[size_t(s)].placement;
    p.binning = kSamplingSchemes[size_t(s)].binning;
}

} // namespace sonarsim

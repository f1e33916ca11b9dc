// The sampling schemes: names for the combinations of ray placement and echo binning (sampling.scheme).
// The one list of them, for the parameter table, the study and the benchmarks.
#pragma once
#include "core/data/scene.hpp"

#include <array>
#include <optional>

namespace sonarsim {

struct NamedSampling {
    SamplingScheme scheme;
    const char* name;
    RayPlacement placement;
    EchoBinning binning;
};

/// In SamplingScheme order. Adaptive placement with point binning has no name: it is rejected
/// (validate_scene), since the adaptive sampler's criteria and error estimate assume footprint binning.
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

// The sampler's rows of the parameter table: rays per beam, normals, placement and binning (and
// sampling.scheme, the name of their combination), the adaptive sampler's target and budget, multipath.
#include "core/scene/param_rows.hpp"

#include "core/scene/sampling_scheme.hpp"

namespace sonarsim::rows {

namespace {

std::vector<std::string> placement_names() {
    std::vector<std::string> out;
    for (const PlacementSpec& p : kRayPlacements) out.push_back(p.name);
    return out;
}

std::string placement_help() {
    std::string out = "Where rays go: ";
    for (const PlacementSpec& p : kRayPlacements)
        out += std::string(&p == &kRayPlacements.front() ? "" : "; ") + p.name + ": " + p.help +
               (p.binning_reason ? " (needs footprint binning)" : "");
    return out;
}

} // namespace

std::vector<ParamSpec> sampling_rows() {
    std::vector<ParamSpec> t;
    t.push_back(integer("sampling.elevation_rays", 1, 1000000, Stage::Trace,
                        "Elevation rays M per beam (jittered: M strata of four rays)",
                        [](S s) -> int& { return s.sampling.elevation_rays; })
                    .with_log_slider(1, 2000));
    t.push_back(
        integer("sampling.azimuth_rays", 1, 1024, Stage::Trace, "Azimuth rays per beam", [](S s) -> int& {
            return s.sampling.azimuth_rays;
        }).with_slider(1, 16));
    t.push_back(enumeration<NormalSource>(
        "sampling.normals", {"mesh", "paper"}, Stage::Trace,
        "Incidence from the true surface normal, or the paper's neighbour-difference normal (eq. 13-14)",
        [](S s) -> NormalSource& { return s.sampling.normals; }));
    // A name for the combination of sampling.placement and sampling.binning.
    ParamSpec scheme =
        blank<ParamSpec>("sampling.scheme", "", ParamType::Enum, Stage::Trace,
                         "Names of sampling.placement + sampling.binning: uniform = grid + point "
                         "(the paper), spread = grid + footprint, adaptive = adaptive + footprint, jittered "
                         "= jittered + footprint");
    for (const NamedSampling& n : kSamplingSchemes) scheme.choices.push_back(n.name);
    scheme.get = [](const SceneDesc& s) {
        const auto named = scheme_of(s.sampling);
        return json(named ? scheme_name(*named) : "adaptive placement with point binning");
    };
    scheme.put = [](SceneDesc& s, const json& v) {
        for (const NamedSampling& n : kSamplingSchemes)
            if (v.get<std::string>() == n.name) set_scheme(s.sampling, n.scheme);
    };
    t.push_back(scheme);
    t.push_back(number("sampling.tolerance_db", "dB", 0, 10, true, false, Stage::Trace,
                       "adaptive: target median |dB error| over echoing bins, as the sampler estimates it; "
                       "it refines until met",
                       [](S s) -> double& { return s.sampling.tolerance_db; })
                    .with_log_slider(0.01, 3));
    t.push_back(number("sampling.tolerance_rel_l1", "", 0, 1, true, false, Stage::Trace,
                       "adaptive: target relative L1 error of the linear image (0.01: 1 %), as the sampler "
                       "estimates it; it refines until both this and tolerance_db are met",
                       [](S s) -> double& { return s.sampling.tolerance_rel_l1; })
                    .with_log_slider(0.001, 0.2)
                    .with_label("rel L1 tolerance"));
    t.push_back(enumeration<ErrorEstimate>(
        "sampling.estimate", {"fast", "strict"}, Stage::Trace,
        "adaptive: what the sampler does with its error estimate (second order on smooth surfaces, first "
        "at edges, plus an azimuth probe: three ray columns against one beside some cells of every 4th "
        "beam, every 8th from 512 beams). fast: refines in elevation and at azimuth edges only, and reports "
        "the probe's share (sampling_error_estimate.azimuth_rel_l1, included in rel_l1); strict: probes "
        "three times as many cells and traces three ray columns per beam where azimuth is the larger share",
        [](S s) -> ErrorEstimate& { return s.sampling.estimate; }));
    t.push_back(integer("sampling.max_rays", 1000, kMaxRaysPerImage, Stage::Trace,
                        "adaptive: budget of rays per image, refinement and passes included; when reached, "
                        "refinement stops and the metadata says so (about 300 bytes of memory per ray)",
                        [](S s) -> int& { return s.sampling.max_rays; })
                    .with_log_slider(1e4, 1e7));
    t.push_back(integer("sampling.bounces", 0, 2, Stage::Trace,
                        "Multipath: specular reflections followed per leg on mirrors (the water surface, "
                        "materials with reflection_db); 0: direct paths only",
                        [](S s) -> int& { return s.sampling.bounces; }));
    return t;
}

/// Keys scene files and `--set` accept that scene_to_json does not write: it writes sampling.scheme, the
/// name of their combination, so that every existing scene's metadata stays as it was.
std::vector<ParamSpec> sampling_input_rows() {
    return {
        enumeration<RayPlacement>("sampling.placement", placement_names(), Stage::Trace, placement_help(),
                                  [](S s) -> RayPlacement& { return s.sampling.placement; }),
        enumeration<EchoBinning>(
            "sampling.binning", {"point", "footprint"}, Stage::Trace,
            "Where a ray's echo goes: point: the bin of its range (the paper); footprint: "
            "spread over the range interval its solid-angle cell covers",
            [](S s) -> EchoBinning& { return s.sampling.binning; }),
    };
}

} // namespace sonarsim::rows

// `sonarsim_bench multipath`: what following specular paths costs. The tank (assets/scenes/tank.json: walls,
// floor and surface mirrors) and the shipwreck under a surface, traced and shaded with sampling.bounces 0, 1
// and 2 (median of repeats, the pose nudged between repeats so that every render re-traces): the adaptive
// sampler at its tolerance (it refines where ghosts need it, so its rays grow too), and the spread scheme on
// fixed rays (the cost per ray of the continuations and shadow rays alone). For the adaptive sampler also
// its error against a dense spread reference with the same bounces (kReferenceRays x kReferenceColumns, at
// the last repeat's pose) and its own estimate of it.
#include "bench.hpp"

#include "core/analysis/reference.hpp"
#include "core/scene/params.hpp"
#include "core/scene/sampling_scheme.hpp"
#include "core/scene/scene_io.hpp"
#include "core/pipeline/simulator.hpp"

#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace sonarsim::bench {

int run_multipath_bench(const std::string& repo, int repeats, const std::vector<std::string>& settings) {
    struct Case {
        std::string name;
        SceneDesc scene;
    };
    std::vector<Case> cases;
    cases.push_back({"tank (Oculus 750 kHz, 256 beams)", load_scene(repo + "/assets/scenes/tank.json")});
    SceneDesc wreck = load_scene(repo + "/assets/scenes/shipwreck.json");
    wreck.water.surface_height_m = wreck.sonar.pose.position_m[2] + 1.0;
    wreck.seafloor->material.reflection_db = 10;
    cases.push_back({"shipwreck + surface 1 m above, floor mirror", wreck});
    for (auto& c : cases)
        for (const auto& a : settings) apply_setting_text(c.scene, a, "--set");
    for (const auto& a : settings) std::printf("--set %s\n", a.c_str());
    std::printf("reference: spread %d x %d with the same bounces (adaptive rows)\n", kReferenceRays,
                kReferenceColumns);
    std::printf("%-44s %-9s %7s %10s %10s %11s %9s %9s %9s %9s\n", "scene", "scheme", "bounces", "rays",
                "mp rays", "trace+shade", "ratio", "rel L1 %", "est. %", "est. dB");
    for (auto& c : cases)
        for (SamplingScheme scheme : {SamplingScheme::Adaptive, SamplingScheme::Spread}) {
            double direct_ms = 0;
            for (int bounces = 0; bounces <= 2; ++bounces) {
                SceneDesc s = c.scene;
                set_scheme(s.sampling, scheme);
                s.sampling.bounces = bounces;
                Simulator sim(s);
                std::vector<double> ms;
                std::shared_ptr<const Frame> f;
                for (int i = 0; i < repeats; ++i) {
                    s.sonar.pose.orientation_deg[2] = c.scene.sonar.pose.orientation_deg[2] + 0.01 * i;
                    sim.set_scene(s);
                    f = sim.render();
                    ms.push_back(f->trace_ms + f->shade_ms);
                }
                std::sort(ms.begin(), ms.end());
                const double med = ms[ms.size() / 2];
                if (bounces == 0) direct_ms = med;
                const auto& est = f->error_estimate;
                std::string errors = "        -         -         -";
                if (scheme == SamplingScheme::Adaptive) {
                    status_line(c.name + ", bounces " + std::to_string(bounces) + ": reference");
                    const ImageError e = error_against_reference(*f, s); // s: the last repeat's pose
                    status_line("");
                    char buf[64];
                    std::snprintf(buf, sizeof buf, "%9.2f %9.2f %9.3f", 100 * e.rel_l1, 100 * est.rel_l1,
                                  est.median_abs_db);
                    errors = buf;
                }
                std::printf("%-44s %-9s %7d %10llu %10llu %8.1f ms %8.2fx %s\n", c.name.c_str(),
                            scheme_name(scheme), bounces, (unsigned long long)f->hits().rays_traced,
                            (unsigned long long)f->hits().multipath_rays, med, med / direct_ms,
                            errors.c_str());
                std::fflush(stdout);
            }
        }
    return 0;
}

} // namespace sonarsim::bench

// `sonarsim_bench multipath`: what following specular paths costs. The tank (assets/scenes/tank.json: walls,
// floor and surface mirrors) and the shipwreck under a surface, traced and shaded with sampling.bounces 0, 1
// and 2 (median of repeats, the pose nudged between repeats so that every render re-traces): the adaptive
// sampler at its tolerance (it refines where ghosts need it, so its rays grow too), and the spread scheme on
// fixed rays (the cost per ray of the continuations and shadow rays alone). Also the error estimate.
#include "bench.hpp"

#include "core/scene/sampling_scheme.hpp"
#include "core/scene/scene_io.hpp"
#include "core/pipeline/simulator.hpp"

#include <algorithm>
#include <cstdio>
#include <vector>

namespace sonarsim::bench {

int run_multipath_bench(const std::string& repo, int repeats) {
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
    std::printf("%-44s %-9s %7s %10s %10s %11s %9s %9s\n", "scene", "scheme", "bounces", "rays", "mp rays",
                "trace+shade", "ratio", "median dB");
    for (auto& c : cases)
        for (SamplingScheme scheme : {SamplingScheme::Adaptive, SamplingScheme::Spread}) {
            double direct_ms = 0;
            for (int bounces = 0; bounces <= 2; ++bounces) {
                SceneDesc s = c.scene;
                set_scheme(s.sampling, scheme);
                s.sampling.bounces = bounces;
                Simulator sim(s);
                std::vector<double> ms;
                std::uint64_t rays = 0, mp_rays = 0;
                double err = 0;
                for (int i = 0; i < repeats; ++i) {
                    s.sonar.pose.orientation_deg[2] = c.scene.sonar.pose.orientation_deg[2] + 0.01 * i;
                    sim.set_scene(s);
                    const auto f = sim.render();
                    ms.push_back(f->trace_ms + f->shade_ms);
                    rays = f->hits().rays_traced, mp_rays = f->hits().multipath_rays;
                    err = f->hits().error_estimate.median_abs_db;
                }
                std::sort(ms.begin(), ms.end());
                const double med = ms[ms.size() / 2];
                if (bounces == 0) direct_ms = med;
                std::printf("%-44s %-9s %7d %10llu %10llu %8.1f ms %8.2fx %9.3f\n", c.name.c_str(),
                            scheme_name(scheme), bounces, (unsigned long long)rays,
                            (unsigned long long)mp_rays, med, med / direct_ms,
                            scheme == SamplingScheme::Adaptive ? err : 0.0);
                std::fflush(stdout);
            }
        }
    return 0;
}

} // namespace sonarsim::bench

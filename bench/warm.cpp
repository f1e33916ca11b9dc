// `sonarsim_bench warm`: the warm image of any scene files (a pose change, every stage rerun; median of
// repeats), its rays, the sampler's own error estimate and the floor (the same number of rays traced and
// shaded as a plain beam-ordered grid), one line per scene. For timing a change on one's own scenes.
#include "bench.hpp"

#include "core/pipeline/simulator.hpp"
#include "core/scene/params.hpp"
#include "core/scene/scene_io.hpp"

#include <cstdio>

namespace sonarsim::bench {

int run_warm_bench(const std::vector<std::string>& scenes, int repeats,
                   const std::vector<std::string>& settings) {
    std::vector<SceneDesc> descs; // every file and setting checked before anything is timed
    for (const auto& file : scenes) {
        descs.push_back(load_scene(file));
        for (const auto& a : settings) apply_setting_text(descs.back(), a, "--set");
    }
    std::printf("| scene | rays | warm ms | floor ms | warm / floor | estimate rel L1 %% | median dB |\n"
                "|---|---:|---:|---:|---:|---:|---:|\n");
    for (size_t k = 0; k < scenes.size(); ++k) {
        const std::string& file = scenes[k];
        const SceneDesc& s = descs[k];
        status_line("warm: " + file + "...");
        Simulator sim(s);
        std::shared_ptr<const Frame> f;
        const double warm = warm_ms(sim, s, repeats, &f);
        const auto& hits = f->hits();
        const double floor = floor_ms(s, hits.rays_traced, repeats);
        status_line("");
        const auto& e = f->error_estimate;
        std::printf("| %s | %llu | %.2f | %.2f | %.2f | %s | %s |\n", file.c_str(),
                    (unsigned long long)hits.rays_traced, warm, floor, warm / floor,
                    e.valid ? std::to_string(100 * e.rel_l1).substr(0, 5).c_str() : "-",
                    e.valid ? std::to_string(e.median_abs_db).substr(0, 6).c_str() : "-");
        std::fflush(stdout);
    }
    return 0;
}

} // namespace sonarsim::bench

// `sonarsim_bench slider`: what dragging one of the viewer's physics sliders costs. While a slider is held
// the viewer asks for previews (TraceControl::preview); a change of a shading value then re-shades the hits
// the last image traced (Stage::Place or Shade) and traces no ray. Per slider: the median wall time of the
// preview image (shade, sensor, full fan) over repeats alternating between two values, the rays those
// previews traced (0 is the target), and the full image the viewer asks for once the slider rests.
#include "bench.hpp"

#include "core/base/timing.hpp"
#include "core/pipeline/simulator.hpp"
#include "core/scene/params.hpp"
#include "core/scene/scene_io.hpp"

#include <chrono>
#include <cstdio>

namespace sonarsim::bench {

namespace {

struct Slider {
    const char* label;
    const char* key;
    double a, b; ///< the two values the drag alternates between
};

} // namespace

int run_slider_bench(const std::vector<std::string>& scenes, int repeats) {
    const Slider sliders[] = {
        {"floor nu", "seafloor.material.nu_db", -30, -40},
        {"floor q", "seafloor.material.q", 1.5, 3},
        {"object nu", "objects.0.material.nu_db", -25, -30},
        {"source level", "sonar.source_level_db", 215, 225},
        {"temperature", "water.temperature_c", 12, 18},
        {"frequency", "sonar.frequency_khz", 900, 1500},
    };
    std::vector<SceneDesc> descs; // every file checked before anything is timed
    for (const auto& file : scenes) descs.push_back(load_scene(file));
    std::printf(
        "| scene | slider | stage | preview ms (median) | shade ms | sensor + fan ms | rays traced by "
        "the previews | full image after rest ms |\n|---|---|---|---:|---:|---:|---:|---:|\n");
    for (size_t k = 0; k < scenes.size(); ++k) {
        for (const Slider& sl : sliders) {
            SceneDesc s = descs[k];
            if (sl.key[0] == 'o' && s.objects.empty()) continue;
            if (sl.key[0] == 's' && sl.key[1] == 'e' && !s.seafloor) continue;
            status_line("slider: " + scenes[k] + " " + sl.label + "...");
            Simulator sim(s);
            sim.render(); // the full image the drag starts from
            TraceControl preview;
            preview.preview = true;
            std::vector<double> ms, shade_ms, image_ms;
            Stage stage = Stage::None;
            const std::uint64_t rays_before = sim.rays_traced();
            for (int i = 0; i < repeats + 2; ++i) {
                SceneDesc t = s;
                apply_setting(t, sl.key, i % 2 ? sl.b : sl.a, "bench");
                stage = changed_stage(s, t);
                s = t;
                const auto t0 = std::chrono::steady_clock::now();
                sim.set_scene(s, stage);
                const auto f = sim.render(preview);
                if (i < 2) continue; // two untimed: buffers warm
                ms.push_back(ms_since(t0));
                shade_ms.push_back(f->shade_ms), image_ms.push_back(f->sensor_ms + f->image_ms);
            }
            const std::uint64_t rays = sim.rays_traced() - rays_before;
            const auto t0 = std::chrono::steady_clock::now();
            sim.render(); // the slider rests: the full image
            const double full = ms_since(t0);
            status_line("");
            std::printf("| %s | %s | %s | %.2f | %.2f | %.2f | %llu | %.1f |\n", scenes[k].c_str(), sl.label,
                        stage == Stage::Place ? "place" : "shade", median(ms), median(shade_ms),
                        median(image_ms), (unsigned long long)rays, full);
            std::fflush(stdout);
        }
    }
    return 0;
}

} // namespace sonarsim::bench

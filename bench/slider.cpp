// `sonarsim_bench slider`: what dragging one of the viewer's physics sliders costs. While a slider is held
// the viewer asks for previews (TraceControl::preview); a change of a shading value then re-shades the hits
// the last image traced (Stage::Place or Shade) and traces no ray. Per slider: the median wall time of the
// preview image (shade, sensor, full fan) over repeats alternating between two values, the rays those
// previews traced (0 is the target), and the full image the viewer asks for once the slider rests: the kept
// hits with their estimate made anew (TraceControl::keep_placement), re-traced only when it misses.
#include "bench.hpp"

#include "core/base/timing.hpp"
#include "core/kinds/ping_series.hpp"
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

struct Timing {
    Stage stage = Stage::None;
    std::vector<double> ms, shade_ms, image_ms;
    std::uint64_t rays = 0;      ///< traced by the previews
    double full_ms = 0;          ///< the full image once the slider rests
    std::uint64_t full_rays = 0; ///< ... the rays it traced (0: the kept hits met the tolerances)
    TraceResult::ErrorEstimate full_estimate; ///< ... its estimate
};

/// Sets the slider's value of step i of the drag in `s`; returns the stage of the change.
Stage drag_to(SceneDesc& s, const Slider& sl, int i) {
    SceneDesc t = s;
    apply_setting(t, sl.key, i % 2 ? sl.b : sl.a, "bench");
    const Stage stage = changed_stage(s, t);
    s = t;
    return stage;
}

/// An imaging sonar: the viewer's worker keeps one Simulator.
Timing time_image(SceneDesc s, const Slider& sl, int repeats) {
    Timing out;
    Simulator sim(s);
    TraceControl full; // the viewer's: the rays kept at rest while their estimate made anew meets
    full.keep_placement = true;
    sim.render(full); // the full image the drag starts from
    TraceControl preview = full;
    preview.preview = true;
    const std::uint64_t rays_before = sim.rays_traced();
    for (int i = 0; i < repeats + 2; ++i) {
        out.stage = drag_to(s, sl, i);
        const auto t0 = std::chrono::steady_clock::now();
        sim.set_scene(s, out.stage);
        const auto f = sim.render(preview);
        if (i < 2) continue; // two untimed: buffers warm
        out.ms.push_back(ms_since(t0));
        out.shade_ms.push_back(f->shade_ms), out.image_ms.push_back(f->sensor_ms + f->image_ms);
    }
    out.rays = sim.rays_traced() - rays_before;
    const std::uint64_t rays_at_rest = sim.rays_traced();
    const auto t0 = std::chrono::steady_clock::now();
    const auto rest = sim.render(full); // the slider rests: the full image
    out.full_ms = ms_since(t0);
    out.full_rays = sim.rays_traced() - rays_at_rest;
    out.full_estimate = rest->error_estimate;
    return out;
}

/// A side-scan's waterfall or a scan's sweep: the viewer's worker keeps the pings' hits (PingTraces). The
/// stages' times are summed over the pings (on every thread).
Timing time_pings(SceneDesc s, const Slider& sl, int repeats) {
    Timing out;
    PingTraces traces;
    PingControl full; // the viewer's: the pings' rays kept at rest while their estimate made anew meets
    full.keep_placement = true;
    render_pings(s, full, &traces);
    PingControl preview = full;
    preview.preview = true;
    for (int i = 0; i < repeats + 2; ++i) {
        out.stage = drag_to(s, sl, i);
        const auto t0 = std::chrono::steady_clock::now();
        const PingSeries p = render_pings(s, preview, &traces);
        out.rays += p.rays_traced;
        if (i < 2) continue;
        out.ms.push_back(ms_since(t0));
        out.shade_ms.push_back(p.stage_ms[1]), out.image_ms.push_back(p.stage_ms[2] + p.stage_ms[3]);
    }
    const auto t0 = std::chrono::steady_clock::now();
    out.full_rays = render_pings(s, full, &traces).rays_traced;
    out.full_ms = ms_since(t0);
    return out;
}

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
        "the previews | full image after rest ms | rays it traced | its estimate rel L1 |\n"
        "|---|---|---|---:|---:|---:|---:|---:|---:|---:|\n");
    for (size_t k = 0; k < scenes.size(); ++k) {
        for (const Slider& sl : sliders) {
            SceneDesc s = descs[k];
            if (sl.key[0] == 'o' && s.objects.empty()) continue;
            if (sl.key[0] == 's' && sl.key[1] == 'e' && !s.seafloor) continue;
            status_line("slider: " + scenes[k] + " " + sl.label + "...");
            const Timing t =
                s.sonar.kind == SonarKind::Imaging ? time_image(s, sl, repeats) : time_pings(s, sl, repeats);
            status_line("");
            char estimate[32] = "-";
            if (t.full_estimate.valid)
                std::snprintf(estimate, sizeof estimate, "%.2f %%%s", 100 * t.full_estimate.rel_l1,
                              t.full_estimate.meets(s.sampling) ? "" : " (misses)");
            std::printf("| %s | %s | %s | %.2f | %.2f | %.2f | %llu | %.1f | %llu | %s |\n",
                        scenes[k].c_str(), sl.label,
                        t.stage == Stage::Place   ? "place"
                        : t.stage <= Stage::Trace ? "trace"
                                                  : "shade",
                        median(t.ms), median(t.shade_ms), median(t.image_ms), (unsigned long long)t.rays,
                        t.full_ms, (unsigned long long)t.full_rays, estimate);
            std::fflush(stdout);
        }
    }
    return 0;
}

} // namespace sonarsim::bench

// One scene measured in its own process (so that its peak memory is its own): each sampling setting timed
// warm (median of repeats of an image after a pose change, through a Simulator), then the dense reference,
// then each setting's error against it.
#include "bench.hpp"

#include "core/display/image.hpp"
#include "core/scene/params.hpp"
#include "core/scene/scene_io.hpp"
#include "core/shading/accumulate.hpp"
#include "core/analysis/study.hpp"
#include "core/pipeline/simulator.hpp"
#include "core/base/timing.hpp"
#include "core/sampling/trace.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sys/resource.h>
#include <unistd.h>

namespace sonarsim::bench {
namespace {

using Clock = std::chrono::steady_clock;

struct Setting {
    Sampling sampling;
    /// "default" (the scene's own), "strict" (the same with sampling.estimate strict), "paper" (uniform
    /// 281), "spread" (the ladder)
    std::string role;
    ErrorEstimate estimate = ErrorEstimate::Fast;
    std::string label() const {
        return sampling.label() + (estimate == ErrorEstimate::Strict ? " strict" : "");
    }
};

/// Default (the scene's sampling), with an adaptive default the same with the strict estimate, the paper's
/// uniform 281 and the spread ladder.
std::vector<Setting> settings(const SceneDesc& s, bool quick) {
    using S = SamplingScheme;
    const Sampling own{*scheme_of(s.sampling), s.sampling.elevation_rays, s.sampling.azimuth_rays};
    std::vector<Setting> v = {{own, "default", s.sampling.estimate}};
    if (own.scheme == S::Adaptive && s.sampling.estimate == ErrorEstimate::Fast)
        v.push_back({own, "strict", ErrorEstimate::Strict});
    auto add = [&](Sampling m, const char* role) {
        for (const Setting& x : v)
            if (x.sampling.scheme == m.scheme && x.sampling.elevation_rays == m.elevation_rays &&
                x.sampling.azimuth_rays == m.azimuth_rays)
                return;
        v.push_back({m, role});
    };
    add({S::Uniform, 281, 1}, "paper");
    std::vector<Sampling> ladder = {{S::Spread, 31, 1}, {S::Spread, 101, 1}, {S::Spread, 281, 1}};
    if (!quick) {
        ladder.push_back({S::Spread, 1001, 1});
        ladder.push_back({S::Spread, 1001, 3});
        ladder.push_back({S::Spread, 3001, 3});
        ladder.push_back({S::Spread, 3001, 9});
    }
    for (const Sampling& m : ladder) add(m, "spread");
    return v;
}

json error_json(const ImageError& e) {
    return {{"rel_l1", e.rel_l1}, {"median_abs_db", e.median_abs_db}, {"p95_abs_db", e.p95_abs_db},
            {"holes", e.holes},   {"spurious", e.spurious},           {"echoing_bins", e.echoing_ref}};
}

/// A setting's images through a Simulator, as `render`, `batch` and the viewer make them after a pose change:
/// the first at the scene's own pose (its ideal image is the one compared with the reference), then warm
/// repeats, the yaw nudged by 0.01 deg each time so that every stage reruns (trace, shade, sensor, display).
/// Timed as this worker did before (trace() and a resampler built once, called directly, after the
/// reference), the bare floor took 11.9 ms where `render` and `sonarsim_bench warm` take 4.5 ms: most of its
/// time went to page faults, the allocator mapping fresh pages for the sampler's buffers on every image.
struct Timed {
    std::shared_ptr<const Frame> first;
    std::vector<double> total, trace, shade, image; ///< per warm repeat [ms]; image: sensor + display
    static double total_of(const Frame& f) { return f.trace_ms + f.shade_ms + f.sensor_ms + f.image_ms; }
};

/// The first image, then as many warm repeats as `budget_ms` allows (from the first's time), within
/// [1, max_repeats]; `repeats` (when > 0) sets their number instead.
Timed time_setting(SceneDesc s, double budget_ms, int max_repeats, int repeats = 0) {
    Timed t;
    Simulator sim(s);
    t.first = sim.render();
    if (repeats <= 0)
        repeats = std::clamp(int(budget_ms / std::max(Timed::total_of(*t.first), 1e-3)), 1, max_repeats);
    const double yaw0 = s.sonar.pose.orientation_deg[2];
    for (int r = 1; r <= repeats; ++r) {
        s.sonar.pose.orientation_deg[2] = yaw0 + 0.01 * r;
        sim.set_scene(s);
        const auto f = sim.render();
        t.total.push_back(Timed::total_of(*f)), t.trace.push_back(f->trace_ms),
            t.shade.push_back(f->shade_ms), t.image.push_back(f->sensor_ms + f->image_ms);
    }
    return t;
}

} // namespace

double self_peak_rss_mb() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_maxrss) / 1024.0;
}

void status_line(const std::string& text) {
    static const bool tty = isatty(fileno(stderr)) != 0;
    if (!tty) return;
    std::fprintf(stderr, "\r\033[K%s", text.c_str());
    std::fflush(stderr);
}

int run_worker(const WorkerOptions& o) {
    // Timed repeats per setting: up to max_repeats, fewer when one image takes long (at least one).
    const int max_repeats = o.quick ? 3 : 7;
    const double budget_ms = o.quick ? 300 : 4000;
    const Sampling dense = o.quick ? Sampling{SamplingScheme::Spread, 729, 9} : kReferenceSampling;

    const SceneDesc scene = load_scene(o.scene_file);
    json out;
    out["scene"] = o.name;
    status_line("  " + o.name + ": loading meshes, building the BVH...");
    auto t0 = Clock::now();
    const SceneGeometry g(scene);
    out["geometry_ms"] = ms_since(t0);
    out["beams"] = scene.sonar.beams;
    out["range_bins"] = scene.sonar.range_bins;

    // Every setting is timed first, after a few untimed images (the process's first images grow its heap
    // and thread pools), and before the reference: timed through a Simulator but with neither, the bare
    // floor still took 7-8 ms; with both, the 4.5-5 ms of `render`.
    const std::vector<Setting> list = settings(scene, o.quick);
    json rows = json::array();
    std::vector<PolarImage> images; // each setting's first image, compared with the reference below
    time_setting(scene, 0, 0, 4);
    for (size_t n = 0; n < list.size(); ++n) {
        const Setting& st = list[n];
        SceneDesc s = scene;
        set_scheme(s.sampling, st.sampling.scheme);
        s.sampling.elevation_rays = st.sampling.elevation_rays;
        s.sampling.azimuth_rays = st.sampling.azimuth_rays;
        s.sampling.estimate = st.estimate;
        status_line("  " + o.name + ": [" + std::to_string(n + 1) + "/" + std::to_string(list.size()) + "] " +
                    st.label());
        const Timed t = time_setting(s, budget_ms, max_repeats);
        const Frame& first = *t.first;
        const auto& e = first.error_estimate;
        const std::uint64_t rays = first.hits().rays_traced;
        json floor = nullptr;
        if (st.sampling.scheme == SamplingScheme::Adaptive) {
            // The floor, timed as the setting is: warm / floor is what the sampler's bookkeeping costs.
            const SceneDesc grid = floor_grid(scene, rays);
            const Timed ft = time_setting(grid, 0, 0, int(t.total.size()));
            floor = {{"elevation_rays", grid.sampling.elevation_rays}, {"warm_ms", median(ft.total)}};
        }
        images.push_back(first.ideal());
        rows.push_back({{"label", st.label()},
                        {"role", st.role},
                        {"scheme", scheme_name(st.sampling.scheme)},
                        {"elevation_rays", st.sampling.elevation_rays},
                        {"azimuth_rays", st.sampling.azimuth_rays},
                        {"sampling_estimate", find_param("sampling.estimate")->get(s)}, // the table's name
                        {"rays", rays},
                        {"repeats", t.total.size()},
                        {"warm_ms", median(t.total)},
                        {"warm_min_ms", *std::min_element(t.total.begin(), t.total.end())},
                        {"trace_ms", median(t.trace)},
                        {"shade_ms", median(t.shade)},
                        {"image_ms", median(t.image)},
                        {"floor", floor},
                        {"estimate", e.valid ? json{{"rel_l1", e.rel_l1},
                                                    {"median_abs_db", e.median_abs_db},
                                                    {"p95_abs_db", e.p95_abs_db},
                                                    {"passes", e.passes}}
                                             : json(nullptr)}});
    }
    const double settings_peak_mb = self_peak_rss_mb();
    // The sector resampler's build, for the report (after the settings: its tables, freed, would also
    // leave the allocator mapping fresh pages for later images).
    t0 = Clock::now();
    { const SectorResampler resampler(scene.sonar, 0); }
    out["resampler_ms"] = ms_since(t0);

    const StudyReference ref = make_reference(
        g, scene,
        [&](double f) { status_line("  " + o.name + ": reference " + std::to_string(int(100 * f)) + " %"); },
        dense);
    out["reference"] = {{"kind", ref.kind},
                        {"description", ref.description},
                        {"time_ms", ref.time_ms},
                        {"rays", ref.rays},
                        {"convergence", error_json(ref.convergence)}};
    out["settings_peak_rss_mb"] = settings_peak_mb;
    for (size_t n = 0; n < images.size(); ++n)
        rows[n]["error"] = error_json(compare_images(images[n], ref.image));
    status_line("");
    out["rows"] = rows;
    out["peak_rss_mb"] = self_peak_rss_mb();
    std::ofstream f(o.json_out, std::ios::trunc);
    f << out.dump(1) << "\n";
    if (!f) {
        std::fprintf(stderr, "sonarsim_bench: cannot write %s\n", o.json_out.c_str());
        return 1;
    }
    return 0;
}

} // namespace sonarsim::bench

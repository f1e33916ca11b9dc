// One scene measured in its own process (so that its peak memory is its own): the dense reference, then each
// sampling setting timed warm (median of repeats of trace + shade + sector image) and compared with it.
#include "bench.hpp"

#include "core/display/image.hpp"
#include "core/scene/params.hpp"
#include "core/scene/scene_io.hpp"
#include "core/shading/accumulate.hpp"
#include "core/analysis/study.hpp"
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

struct Timed {
    PolarImage polar;
    TraceResult::ErrorEstimate estimate;
    std::uint64_t rays = 0;
    double trace_ms = 0, shade_ms = 0, image_ms = 0;
    double total() const { return trace_ms + shade_ms + image_ms; }
};

/// One image as the Simulator makes it after a pose change: trace, shade (unless the tracer already did),
/// sector image from the cached resampling taps.
Timed render_once(const SceneGeometry& g, const SceneDesc& s, const SectorResampler& resampler) {
    Timed r;
    auto t0 = Clock::now();
    TraceResult t = trace(g, s);
    r.trace_ms = ms_since(t0);
    t0 = Clock::now();
    r.polar = t.shaded ? *t.shaded->image : shade(t, s);
    r.shade_ms = ms_since(t0);
    r.rays = t.rays_traced;
    r.estimate = t.error_estimate;
    t = TraceResult{};
    t0 = Clock::now();
    const Image8 sector = resampler.apply(r.polar, s.display);
    r.image_ms = ms_since(t0);
    if (sector.pixels.empty()) r.image_ms = -1; // never: keeps the call from being optimised away
    return r;
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
    t0 = Clock::now();
    const SectorResampler resampler(scene.sonar, 0);
    out["resampler_ms"] = ms_since(t0);
    out["beams"] = scene.sonar.beams;
    out["range_bins"] = scene.sonar.range_bins;

    const StudyReference ref = make_reference(
        g, scene,
        [&](double f) { status_line("  " + o.name + ": reference " + std::to_string(int(100 * f)) + " %"); },
        dense);
    out["reference"] = {{"kind", ref.kind},
                        {"description", ref.description},
                        {"time_ms", ref.time_ms},
                        {"rays", ref.rays},
                        {"convergence", error_json(ref.convergence)}};
    out["reference_peak_rss_mb"] = self_peak_rss_mb();

    const std::vector<Setting> list = settings(scene, o.quick);
    json rows = json::array();
    for (size_t n = 0; n < list.size(); ++n) {
        const Setting& st = list[n];
        SceneDesc s = scene;
        set_scheme(s.sampling, st.sampling.scheme);
        s.sampling.elevation_rays = st.sampling.elevation_rays;
        s.sampling.azimuth_rays = st.sampling.azimuth_rays;
        s.sampling.estimate = st.estimate;
        status_line("  " + o.name + ": [" + std::to_string(n + 1) + "/" + std::to_string(list.size()) + "] " +
                    st.label());
        // The first image warms caches and the allocator; its image is the one compared with the reference.
        const Timed first = render_once(g, s, resampler);
        const int repeats = std::clamp(int(budget_ms / std::max(first.total(), 1e-3)), 1, max_repeats);
        std::vector<double> total, tr, sh, im;
        for (int r = 0; r < repeats; ++r) {
            const Timed t = render_once(g, s, resampler);
            total.push_back(t.total()), tr.push_back(t.trace_ms), sh.push_back(t.shade_ms),
                im.push_back(t.image_ms);
        }
        const auto& e = first.estimate;
        json floor = nullptr;
        if (st.sampling.scheme == SamplingScheme::Adaptive) {
            // The floor, timed as the setting is: warm / floor is what the sampler's bookkeeping costs.
            const SceneDesc grid = floor_grid(scene, first.rays);
            render_once(g, grid, resampler);
            std::vector<double> ft;
            for (int r = 0; r < repeats; ++r) ft.push_back(render_once(g, grid, resampler).total());
            floor = {{"elevation_rays", grid.sampling.elevation_rays}, {"warm_ms", median(ft)}};
        }
        rows.push_back({{"label", st.label()},
                        {"role", st.role},
                        {"scheme", scheme_name(st.sampling.scheme)},
                        {"elevation_rays", st.sampling.elevation_rays},
                        {"azimuth_rays", st.sampling.azimuth_rays},
                        {"sampling_estimate", find_param("sampling.estimate")->get(s)}, // the table's name
                        {"rays", first.rays},
                        {"repeats", repeats},
                        {"warm_ms", median(total)},
                        {"warm_min_ms", *std::min_element(total.begin(), total.end())},
                        {"trace_ms", median(tr)},
                        {"shade_ms", median(sh)},
                        {"image_ms", median(im)},
                        {"floor", floor},
                        {"error", error_json(compare_images(first.polar, ref.image))},
                        {"estimate", e.valid ? json{{"rel_l1", e.rel_l1},
                                                    {"median_abs_db", e.median_abs_db},
                                                    {"p95_abs_db", e.p95_abs_db},
                                                    {"passes", e.passes}}
                                             : json(nullptr)}});
    }
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

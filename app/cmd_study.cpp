// `sonarsim study`: work-precision report. For a ladder of sampling settings, render, time (median of
// repeats) and measure the error against a reference; print a table, write CSV and a log-log plot of error vs
// time.
#include "commands.hpp"
#include "load.hpp"
#include "plot.hpp"
#include "status_line.hpp"

#include "core/io/output.hpp"
#include "core/analysis/study.hpp"
#include "core/scene/sampling_scheme.hpp"

#include <array>

#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>
#include <sys/resource.h>
#include <unistd.h>

namespace sonarsim::app {
namespace {

struct StudyOptions {
    SceneOptions scene;
    std::string out = "study";
    int repeats = 5;
    bool quick = false;
};

std::string fmt(const char* f, double v) {
    char b[64];
    std::snprintf(b, sizeof b, f, v);
    return b;
}

/// Peak resident set size of this process so far [MB].
double peak_rss_mb() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_maxrss) / 1024.0; // Linux: kilobytes
}

int run_study(const StudyOptions& o) {
    const SceneDesc scene = load_scene_from_options(o.scene);
    StatusLine status;
    status.show("loading the scene and building the BVH...");
    const SceneGeometry geometry(scene);
    const StudyReference ref = make_reference(geometry, scene, [&](double f) {
        status.show("reference: " + fmt("%.0f", 100 * f) + " % (then " +
                    std::to_string(default_ladder(o.quick).size() + 1) + " sampling settings)");
    });
    status.clear();
    std::cout << "reference: " << ref.kind << " (" << ref.description << "), " << fmt("%.0f", ref.time_ms)
              << " ms" << (ref.rays ? ", " + fmt("%.0f", double(ref.rays)) + " rays" : std::string())
              << "\n  its own convergence (coarser version vs reference): rel L1 "
              << fmt("%.2e", ref.convergence.rel_l1) << ", median "
              << fmt("%.2e", ref.convergence.median_abs_db) << " dB, p95 "
              << fmt("%.2e", ref.convergence.p95_abs_db) << " dB; echoing bins "
              << ref.convergence.echoing_ref << "\n  peak memory so far: " << fmt("%.0f", peak_rss_mb())
              << " MB\n";

    std::vector<Sampling> ladder = default_ladder(o.quick);
    ladder.push_back(
        {*scheme_of(scene.sampling), scene.sampling.elevation_rays, scene.sampling.azimuth_rays});
    std::ostringstream csv;
    csv << "label,scheme,elevation_rays,azimuth_rays,rays,time_ms,rel_l1,median_abs_db,p95_abs_db,holes,"
           "echoing_bins,estimated_rel_l1,estimated_median_db\n";
    std::printf("%-22s %10s %9s %10s %9s %9s %7s %10s\n", "sampling", "rays", "time_ms", "rel_L1_%", "med_dB",
                "p95_dB", "holes", "est_L1_%");
    // One series per scheme (kSamplingSchemes order, the index of r.sampling.scheme), then the scene's own.
    const std::array<std::array<unsigned char, 3>, kSamplingSchemes.size()> colours = {
        {{214, 39, 40}, {31, 119, 180}, {44, 160, 44}, {148, 103, 189}}};
    std::vector<Series> series;
    for (const NamedSampling& n : kSamplingSchemes)
        series.push_back({std::string(n.name) + (n.scheme == SamplingScheme::Uniform ? " (paper)" : ""),
                          colours[size_t(n.scheme)],
                          {}});
    series.push_back({"scene setting", {0, 0, 0}, {}});
    for (size_t n = 0; n < ladder.size(); ++n) {
        const bool is_default = n + 1 == ladder.size();
        status.show("[" + std::to_string(n + 1) + "/" + std::to_string(ladder.size()) + "] " +
                    ladder[n].label() + " x " + std::to_string(o.repeats) + " repeats...");
        const StudyRow r = measure(geometry, scene, ladder[n], o.repeats, ref.image);
        status.clear();
        const std::string label = (is_default ? "scene: " : "") + r.sampling.label();
        std::printf("%-22s %10.0f %9.2f %10.4f %9.4f %9.4f %7ld %10s\n", label.c_str(), r.rays, r.time_ms,
                    100 * r.error.rel_l1, r.error.median_abs_db, r.error.p95_abs_db, r.error.holes,
                    r.estimate.valid ? fmt("%.4f", 100 * r.estimate.rel_l1).c_str() : "-");
        csv << label << "," << int(r.sampling.scheme) << "," << r.sampling.elevation_rays << ","
            << r.sampling.azimuth_rays << "," << r.rays << "," << r.time_ms << "," << r.error.rel_l1 << ","
            << r.error.median_abs_db << "," << r.error.p95_abs_db << "," << r.error.holes << ","
            << r.error.echoing_ref << "," << (r.estimate.valid ? r.estimate.rel_l1 : -1) << ","
            << (r.estimate.valid ? r.estimate.median_abs_db : -1) << "\n";
        const double y = std::max(100 * r.error.rel_l1, 1e-6);
        series[is_default ? kSamplingSchemes.size() : size_t(r.sampling.scheme)].points.emplace_back(
            r.time_ms, y);
    }
    const std::string title =
        "sonarsim study: " + (o.scene.scene_file.empty() ? "default scene" : o.scene.scene_file) +
        "  (reference: " + ref.kind + ")";
    const Image8 plot =
        loglog_plot(series, title, "time per image [ms] (trace + shade, median)", "relative L1 error [%]");
    write_files_atomically({{o.out + ".csv", to_bytes(csv.str())}, {o.out + ".png", encode_png(plot)}});
    std::cout << "wrote " << o.out << ".csv and " << o.out << ".png\n"
              << "peak memory (max resident set size of this process): " << fmt("%.0f", peak_rss_mb())
              << " MB\n";
    return 0;
}

} // namespace

void register_study(CLI::App& app, std::function<int()>& run) {
    auto o = std::make_shared<StudyOptions>();
    CLI::App* cmd = app.add_subcommand(
        "study",
        "Work-precision report: error against a reference vs time for a ladder of sampling settings");
    add_scene_options(*cmd, o->scene);
    cmd->add_option("--out", o->out, "Output prefix: PREFIX.csv and PREFIX.png (log-log plot)")
        ->capture_default_str();
    cmd->add_option("--repeats", o->repeats, "Timing repeats per setting (median is reported)")
        ->capture_default_str()
        ->check(CLI::Range(1, 1000));
    cmd->add_flag("--quick", o->quick, "Leave out the densest settings");
    cmd->callback([o, &run] { run = [o] { return run_study(*o); }; });
}

} // namespace sonarsim::app

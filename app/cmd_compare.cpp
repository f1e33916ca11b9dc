// `sonarsim compare A B`: realism statistics of two sonar images (an .aris frame, a level .npy or a gray fan
// PNG each), printed as a table and written as JSON plus a plot (core/analysis/compare.hpp says what each
// number is).
#include "commands.hpp"
#include "plot.hpp"

#include "core/analysis/compare_report.hpp"
#include "core/io/output.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>

namespace sonarsim::app {
namespace {

struct CompareArgs {
    std::string a, b, out;
    std::size_t frame_a = 0, frame_b = 0;
    std::string fan_a, fan_b;
};

std::string cell(const nlohmann::json& v, const char* fmt = "%.3f") {
    if (!v.is_number()) return "-";
    char buf[32];
    std::snprintf(buf, sizeof buf, fmt, v.get<double>());
    return buf;
}

void print_table(const nlohmann::json& r, const CompareArgs& c) {
    const nlohmann::json &a = r["a"], &b = r["b"], &p = r["pair"];
    std::printf("A: %s (frame %zu), %d bins x %d beams\nB: %s (frame %zu), %d bins x %d beams\n\n",
                c.a.c_str(), c.frame_a, a["bins"].get<int>(), a["beams"].get<int>(), c.b.c_str(), c.frame_b,
                b["bins"].get<int>(), b["beams"].get<int>());
    std::printf("%-44s %10s %10s\n", "", "A", "B");
    auto row = [&](const char* name, const nlohmann::json& x, const nlohmann::json& y,
                   const char* fmt = "%.3f") {
        std::printf("%-44s %10s %10s\n", name, cell(x, fmt).c_str(), cell(y, fmt).c_str());
    };
    row("samples at the floor", a["floor_fraction"], b["floor_fraction"]);
    row("mean level [dB]", a["mean_level_db"], b["mean_level_db"], "%.1f");
    row("speckle contrast, intensity (Rayleigh: 1)", a["contrast_intensity"], b["contrast_intensity"]);
    row("speckle contrast, amplitude (Rayleigh: 0.523)", a["contrast_amplitude"], b["contrast_amplitude"]);
    const char* q[] = {"5", "25", "50", "75", "95"};
    for (int i = 0; i < 5; ++i)
        row(("dB around the local mean, " + std::string(q[i]) + "th pct").c_str(), a["quantiles_db"][i],
            b["quantiles_db"][i], "%.2f");
    for (int lag = 0; lag < int(a["grain_range"].size()); ++lag) {
        row(("grain along range, lag " + std::to_string(lag + 1)).c_str(), a["grain_range"][lag],
            b["grain_range"][lag]);
    }
    for (int lag = 0; lag < int(a["grain_beams"].size()); ++lag)
        row(("grain across beams, lag " + std::to_string(lag + 1)).c_str(), a["grain_beams"][lag],
            b["grain_beams"][lag]);
    std::printf("\nrange profile, rms difference [dB]            %10s\n",
                cell(p["profile_rms_db"], "%.2f").c_str());
    std::printf("histogram distance (total variation, 0..1)    %10s\n",
                cell(p["histogram_distance"]).c_str());
    if (p["aligned"].get<bool>()) {
        std::printf("correlation of the dB images                  %10s\n", cell(p["correlation"]).c_str());
        std::printf("highlight overlap (IoU, above 90th pct)       %10s\n",
                    cell(p["highlight_overlap"]).c_str());
        std::printf("shadow overlap (IoU, floor or below 10th pct) %10s\n",
                    cell(p["shadow_overlap"]).c_str());
    } else {
        std::printf("(different grids: no per-sample correlation or overlaps)\n");
    }
}

Image8 plot(const nlohmann::json& r, const CompareOptions& o) {
    const std::array<std::uint8_t, 3> blue{31, 119, 180}, orange{255, 127, 14};
    Series pa{"A", blue, {}}, pb{"B", orange, {}}, ha{"A", blue, {}}, hb{"B", orange, {}};
    auto profile = [](const nlohmann::json& v, Series& s) {
        for (size_t i = 0; i < v.size(); ++i)
            s.points.push_back({(i + 0.5) / double(v.size()), v[i].is_number() ? v[i].get<double>() : NAN});
    };
    profile(r["a"]["range_profile_db"], pa), profile(r["b"]["range_profile_db"], pb);
    auto hist = [&](const nlohmann::json& v, Series& s) {
        for (size_t i = 0; i < v.size(); ++i)
            s.points.push_back({o.histogram_lo_db + (i + 0.5) * o.histogram_step_db,
                                v[i].get<double>() / o.histogram_step_db});
    };
    hist(r["a"]["histogram"], ha), hist(r["b"]["histogram"], hb);
    return stack_vertically({linear_plot({pa, pb}, "mean level against range, over the image's mean",
                                         "fraction of the range window", "dB", 900, 420),
                             linear_plot({ha, hb}, "speckle: level around the local mean",
                                         "10 log10(I / local mean) [dB]", "density per dB", 900, 420)});
}

} // namespace

void register_compare(CLI::App& app, std::function<int()>& run) {
    auto c = std::make_shared<CompareArgs>();
    CLI::App* cmd = app.add_subcommand(
        "compare", "Realism statistics of two sonar images (an .aris frame, a level .npy or a gray fan PNG "
                   "each): mean level "
                   "against range, speckle contrast and grain, dB quantiles, floor, histogram distance");
    cmd->add_option("a", c->a, "First image: FILE.aris, FILE.npy or FILE.png (e.g. a real recording)")
        ->required();
    cmd->add_option("b", c->b, "Second image: FILE.aris, FILE.npy or FILE.png (e.g. a simulated frame)")
        ->required();
    cmd->add_option("--frame-a", c->frame_a, "Frame of A when it is an .aris recording (from 0)");
    cmd->add_option("--frame-b", c->frame_b, "Frame of B when it is an .aris recording (from 0)");
    const char* fan = "Geometry of a fan PNG: apex_x_px,apex_y_px,px_per_m,azimuth_fov_deg,range_min_m,"
                      "range_max_m,lo_db,hi_db,beams,bins (apex pixel, scale, fan, the levels of gray 0 and "
                      "255, the grid to sample onto); default: the metadata render wrote beside the PNG";
    cmd->add_option("--fan-a", c->fan_a, fan);
    cmd->add_option("--fan-b", c->fan_b, fan);
    cmd->add_option("--out", c->out, "Also write PREFIX.json (every number) and PREFIX.png (the plots)");
    cmd->callback([&run, c] {
        run = [c] {
            const CompareOptions o;
            const PolarImage a = load_compare_image(c->a, c->frame_a, c->fan_a),
                             b = load_compare_image(c->b, c->frame_b, c->fan_b);
            nlohmann::json r = compare_images_report(a, b, o);
            r["a"]["file"] = c->a, r["a"]["frame"] = c->frame_a;
            r["b"]["file"] = c->b, r["b"]["frame"] = c->frame_b;
            print_table(r, *c);
            if (!c->out.empty()) {
                const std::string text = r.dump(2) + "\n";
                write_files_atomically({{c->out + ".json", Bytes(text.begin(), text.end())},
                                        {c->out + ".png", encode_png(plot(r, o))}});
                std::printf("\nwrote %s.json and %s.png\n", c->out.c_str(), c->out.c_str());
            }
            return 0;
        };
    });
}

} // namespace sonarsim::app

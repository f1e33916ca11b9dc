// sonarsim_bench: runs every benchmark scene, each in its own process, and writes RESULTS.md, results.csv and
// results.json (see bench/README.md). Subcommands used by the driver itself: `worker` (one scene) and
// `terrain` (write a procedural terrain PLY).
#include "bench.hpp"
#include "terrain.hpp"

#include "core/base/errors.hpp"
#include "core/base/timing.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <sys/resource.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

namespace sonarsim::bench {
namespace fs = std::filesystem;
namespace {

/// Wall time the viewer timing of one scene may take, roughly [s].
constexpr double kViewBudget_s = 120;

struct DriverOptions {
    Paths paths;
    std::string out;
    std::vector<std::string> only;
    bool quick = false, no_view = false, no_devices = false;
    int view_frames = 150, device_repeats = 3;
    std::string command; ///< as typed, for the report
};

struct Child {
    int status = -1;    ///< exit status, or -1 when it did not exit normally
    double wall_ms = 0; ///< from fork to exit
    double peak_mb = 0; ///< its ru_maxrss
};

/// Runs argv[0] (searched in PATH) with stdout and stderr redirected to files ("" keeps ours) and waits.
Child run_child(const std::vector<std::string>& argv, const std::string& out_file,
                const std::string& err_file) {
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    Child c;
    const auto t0 = std::chrono::steady_clock::now();
    const pid_t pid = fork();
    if (pid < 0) return c;
    if (pid == 0) {
        auto redirect = [](const std::string& file, int fd) {
            if (file.empty()) return;
            const int f = open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
            if (f >= 0) dup2(f, fd), close(f);
        };
        redirect(out_file, STDOUT_FILENO);
        redirect(err_file, STDERR_FILENO);
        execvp(args[0], args.data());
        std::perror(args[0]);
        _exit(127);
    }
    int status = 0;
    rusage ru{};
    while (wait4(pid, &status, 0, &ru) < 0)
        if (errno != EINTR) return c;
    c.wall_ms = ms_since(t0);
    c.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    c.peak_mb = double(ru.ru_maxrss) / 1024.0;
    return c;
}

std::string self_exe() {
    std::error_code ec;
    const fs::path p = fs::read_symlink("/proc/self/exe", ec);
    return ec ? std::string("sonarsim_bench") : p.string();
}

std::string read_text(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

/// First line of a command's output ("" when it fails).
std::string command_line_output(const std::string& cmd) {
    std::string out;
    if (FILE* f = popen(cmd.c_str(), "r")) {
        char b[512];
        if (std::fgets(b, sizeof b, f)) out = b;
        pclose(f);
    }
    while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
    return out;
}

double load_average() {
    double l = NAN;
    if (FILE* f = std::fopen("/proc/loadavg", "r")) {
        if (std::fscanf(f, "%lf", &l) != 1) l = NAN;
        std::fclose(f);
    }
    return l;
}

std::string cpu_model() {
    std::ifstream in("/proc/cpuinfo");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
    return "unknown CPU";
}

bool have_program(const std::string& name) {
    return std::system(("command -v " + name + " >/dev/null 2>&1").c_str()) == 0;
}

std::string quoted(const std::vector<std::string>& argv) {
    std::string s;
    for (const std::string& a : argv)
        s += (s.empty() ? "" : " ") + (a.find(' ') == std::string::npos ? a : "'" + a + "'");
    return s;
}

std::string safe_label(std::string s) {
    for (char& c : s)
        if (c == ' ') c = '_';
    return s;
}

/// `sonarsim view --orbit` under xvfb-run: the JSON line it prints at exit.
json run_view(const Paths& p, const BenchScene& sc, int frames) {
    const std::string out = p.work + "/logs/" + sc.name + "_view.out",
                      err = p.work + "/logs/" + sc.name + "_view.err";
    const Child c = run_child({"xvfb-run", "-a", "-s", "-screen 0 1280x800x24", p.sonarsim, "view", "--scene",
                               sc.file, "--orbit", "--frames", std::to_string(frames)},
                              out, err);
    std::istringstream lines(read_text(out));
    std::string line, last;
    while (std::getline(lines, line))
        if (!line.empty() && line[0] == '{') last = line;
    json v;
    try {
        v = json::parse(last);
    } catch (const std::exception&) {
        return {{"error", "no timing line (exit status " + std::to_string(c.status) + "; see " + err + ")"}};
    }
    v["wall_s"] = c.wall_ms / 1000;
    return v;
}

int run_driver(const DriverOptions& o) {
    const auto t_start = std::chrono::steady_clock::now();
    const Paths& p = o.paths;
    for (const char* d : {"", "/logs", "/results", "/render", "/scenes"}) fs::create_directories(p.work + d);
    fs::create_directories(o.out);
    if (!fs::exists(p.sonarsim)) {
        std::cerr << "sonarsim_bench: " << p.sonarsim << " not found (build the sonarsim target first)\n";
        return 1;
    }
    auto log = [](const std::string& s) { std::cout << s << std::endl; };
    const std::vector<std::string> names = {"fig9",     "floor", "terrain200k", "terrain2M", "shipwreck",
                                            "monterey", "bunny", "oculus",      "rough",     "objects"};
    for (const std::string& n : o.only)
        if (std::find(names.begin(), names.end(), n) == names.end()) {
            std::cerr << "sonarsim_bench: unknown scene \"" << n << "\"; scenes:";
            for (const std::string& s : names) std::cerr << " " << s;
            std::cerr << "\n";
            return 2;
        }
    auto wanted = [&](const BenchScene& s) {
        if (!o.only.empty()) return std::find(o.only.begin(), o.only.end(), s.name) != o.only.end();
        return !(o.quick && s.heavy);
    };
    std::vector<BenchScene> scenes = prepare_scenes(p, wanted, log);

    json meta;
    {
        std::time_t now = std::time(nullptr);
        char b[64];
        std::strftime(b, sizeof b, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
        meta["started_utc"] = b;
    }
    meta["quick"] = o.quick;
    meta["commit"] = command_line_output("git -C '" + p.repo + "' rev-parse --short HEAD 2>/dev/null");
    meta["dirty"] =
        !command_line_output("git -C '" + p.repo +
                             "' status --porcelain --untracked-files=no -- . ':!bench/results' 2>/dev/null")
             .empty(); // the results themselves are this run's output
    meta["cpu"] = cpu_model();
    meta["threads"] = std::thread::hardware_concurrency();
    meta["loadavg_start"] = load_average();
    meta["command"] = o.command;
    const bool xvfb = have_program("xvfb-run");
    const bool view = xvfb && !o.quick && !o.no_view;
    meta["view_note"] =
        view ? "Software OpenGL (Mesa llvmpipe) on this machine; " + std::to_string(o.view_frames) +
                   " frames, fewer when one default image takes so long that they would exceed ~" +
                   std::to_string(int(kViewBudget_s)) + " s (the frames column says how many were timed)."
             : (xvfb ? "--quick or --no-view" : "xvfb-run not found");

    std::vector<BenchScene> todo;
    for (const BenchScene& s : scenes)
        if (wanted(s)) todo.push_back(s);

    json all = json::array();
    for (size_t i = 0; i < todo.size(); ++i) {
        const BenchScene& sc = todo[i];
        json j = {{"name", sc.name}, {"title", sc.title}, {"file", sc.file}, {"triangles", sc.triangles}};
        std::string shown = sc.file;
        if (shown.rfind(p.repo + "/", 0) == 0)
            shown = shown.substr(p.repo.size() + 1);
        else if (shown.rfind(p.work + "/", 0) == 0)
            shown = "<work>/" + shown.substr(p.work.size() + 1) + " (generated)";
        j["file_shown"] = shown;
        std::cout << "[" << i + 1 << "/" << todo.size() << "] " << sc.name << ": " << sc.title << std::endl;
        if (!sc.skip.empty()) {
            std::cout << "  skipped: " << sc.skip << std::endl;
            j["skip"] = sc.skip;
            all.push_back(j);
            continue;
        }
        if (sc.view_only) {
            j["view_only"] = true;
            if (view) {
                status_line("  " + sc.name + ": sonarsim view --orbit --frames " +
                            std::to_string(o.view_frames) + " under xvfb-run...");
                j["view"] = run_view(p, sc, o.view_frames);
                status_line("");
                std::cout << "  done: viewer only" << std::endl;
            } else {
                std::cout << "  viewer only: not run (" << meta["view_note"].get<std::string>() << ")"
                          << std::endl;
            }
            all.push_back(j);
            continue;
        }
        const auto t0 = std::chrono::steady_clock::now();
        const std::string wjson = p.work + "/results/" + sc.name + ".json";
        fs::remove(wjson);
        std::vector<std::string> wargs = {self_exe(), "worker", sc.name, sc.file, wjson};
        if (o.quick) wargs.push_back("--quick");
        const Child w = run_child(wargs, "", "");
        if (w.status != 0 || !fs::exists(wjson)) {
            j["error"] = "worker failed (exit status " + std::to_string(w.status) + ")";
            std::cout << "  " << j["error"].get<std::string>() << std::endl;
            all.push_back(j);
            continue;
        }
        const json res = json::parse(read_text(wjson));
        for (auto it = res.begin(); it != res.end(); ++it) j[it.key()] = it.value();
        j["process_peak_mb"] = w.peak_mb;

        // First image: a whole `sonarsim render` process per setting, run one at a time.
        for (json& r : j["rows"]) {
            status_line("  " + sc.name + ": sonarsim render, " + r["label"].get<std::string>());
            const std::string prefix = p.work + "/render/" + sc.name + "_" + safe_label(r["label"]);
            const Child c = run_child(
                {p.sonarsim, "render", "--scene", sc.file, "--set",
                 "sampling.scheme=" + r["scheme"].get<std::string>(), "--set",
                 "sampling.elevation_rays=" + std::to_string(r["elevation_rays"].get<int>()), "--set",
                 "sampling.azimuth_rays=" + std::to_string(r["azimuth_rays"].get<int>()), "--set",
                 "sampling.estimate=" + r.at("sampling_estimate").get<std::string>(), "--out", prefix},
                p.work + "/logs/" + sc.name + "_render.log", p.work + "/logs/" + sc.name + "_render.err");
            if (c.status == 0) {
                r["first_image_ms"] = c.wall_ms;
                r["render_peak_mb"] = c.peak_mb;
                // What `sonarsim render` wrote in its metadata, for cross-checking the in-process numbers.
                try {
                    const json meta = json::parse(read_text(prefix + ".json"));
                    r["render_rays"] = meta["rays_traced"];
                    r["render_sampling_error_estimate"] = meta["sampling_error_estimate"];
                } catch (const std::exception&) {
                    r["render_rays"] = nullptr;
                }
            } else {
                r["render_error"] = "exit status " + std::to_string(c.status);
            }
        }
        status_line("");
        const json* d = nullptr;
        for (const json& r : j["rows"])
            if (r["role"] == "default") d = &r;
        if (view && sc.view) {
            // Every orbit frame waits for a new default image, while the viewer draws on the other core: a
            // frame takes about twice the warm image time. Cap the frames so the timing takes ~2 min.
            const double frame_ms = 2 * std::max(1.0, (*d)["warm_ms"].get<double>());
            const int frames =
                std::clamp(int(kViewBudget_s * 1000 / frame_ms), std::min(30, o.view_frames), o.view_frames);
            status_line("  " + sc.name + ": sonarsim view --orbit --frames " + std::to_string(frames) +
                        " under xvfb-run...");
            j["view"] = run_view(p, sc, frames);
            status_line("");
        }
        char line[400];
        std::snprintf(
            line, sizeof line,
            "  done in %.0f s: reference converged to %.2g rel L1; default %s: %.4g ms warm, %.4g ms first "
            "image, rel L1 %.3g %%; process peak %.0f MB",
            ms_since(t0) / 1000, j["reference"]["convergence"]["rel_l1"].get<double>(),
            (*d)["label"].get<std::string>().c_str(), (*d)["warm_ms"].get<double>(),
            d->value("first_image_ms", NAN), 100 * (*d)["error"]["rel_l1"].get<double>(), w.peak_mb);
        std::cout << line << std::endl;
        all.push_back(j);
    }
    json devices;
    if (!o.quick && !o.no_devices && o.only.empty()) {
        // Every device preset over the terrain and the wreck, in its own process like the scenes; its rows
        // print as they are measured.
        std::cout << "[devices] every device preset at its own window, over the terrain and the wreck"
                  << std::endl;
        const std::string djson = p.work + "/results/devices.json";
        fs::remove(djson);
        const Child c = run_child({self_exe(), "--work", p.work, "--repo", p.repo, "devices", "--repeats",
                                   std::to_string(o.device_repeats), "--json", djson},
                                  "", "");
        devices = c.status == 0 && fs::exists(djson)
                      ? json::parse(read_text(djson))
                      : json{{"error", "exit status " + std::to_string(c.status)}};
        devices["wall_s"] = c.wall_ms / 1000;
    }
    meta["loadavg_end"] = load_average();
    meta["wall_s"] = ms_since(t_start) / 1000;
    json results = {{"meta", meta}, {"scenes", all}};
    if (!devices.is_null()) results["devices"] = devices;
    const std::string md = write_reports(results, o.out);
    std::cout << "\nwrote " << o.out << "/RESULTS.md, results.csv, results.json\n";
    // The summary table on the terminal.
    const size_t a = md.find("## Summary"), b = md.find("## Per scene");
    if (a != std::string::npos && b != std::string::npos) std::cout << "\n" << md.substr(a, b - a);
    for (const json& sc : all)
        if (sc.contains("error")) return 1;
    return devices.contains("error") ? 1 : 0;
}

} // namespace
} // namespace sonarsim::bench

int main(int argc, char** argv) {
    using namespace sonarsim::bench;
    namespace fs = std::filesystem;
    CLI::App app{
        "sonarsim_bench: the sonarsim benchmark suite (speed, memory and accuracy on realistic scenes)"};
    DriverOptions o;
    const fs::path exe_dir = fs::path(self_exe()).parent_path();
    o.paths.repo = SONARSIM_SOURCE_DIR;
    o.paths.sonarsim = (exe_dir / "sonarsim").string();
    o.paths.work = (exe_dir / "bench").string();
    app.add_flag("--quick", o.quick,
                 "Smoke run: fewer settings and repeats, lighter reference, no heavy scenes, no viewer");
    app.add_option("--scenes", o.only,
                   "Only these scenes (comma-separated): fig9, floor, terrain200k, terrain2M, "
                   "shipwreck, monterey, bunny, oculus, rough, objects")
        ->delimiter(',');
    app.add_option("--out", o.out,
                   "Where RESULTS.md, results.csv, results.json go (default: REPO/bench/results; "
                   "with --quick: WORK/quick-results)");
    app.add_option("--work", o.paths.work, "Work directory: terrains, scene files, renders, logs")
        ->capture_default_str();
    app.add_option("--repo", o.paths.repo, "Source checkout")->capture_default_str();
    app.add_option("--shared", o.paths.shared, "Shared mesh collection (default: REPO/../shared)");
    app.add_option("--sonarsim", o.paths.sonarsim, "The sonarsim executable")->capture_default_str();
    app.add_flag("--no-view", o.no_view, "Skip the viewer timings");
    app.add_flag("--no-devices", o.no_devices,
                 "Skip the device presets' table (also skipped with --quick or --scenes)");
    app.add_option("--device-repeats", o.device_repeats, "Repeats of each device preset's warm image")
        ->capture_default_str();
    app.add_option("--view-frames", o.view_frames, "Frames of each viewer timing")->capture_default_str();

    WorkerOptions w;
    CLI::App* worker = app.add_subcommand("worker", "(internal) measure one scene in this process");
    worker->add_option("name", w.name)->required();
    worker->add_option("scene_file", w.scene_file)->required();
    worker->add_option("json_out", w.json_out)->required();
    worker->add_flag("--quick", w.quick);

    std::string terrain_out;
    int grid = 317;
    CLI::App* terrain = app.add_subcommand("terrain", "Write the procedural terrain as a binary PLY");
    terrain->add_option("--grid", grid, "Vertices per side (317: ~200 k triangles, 1001: 2 M)")
        ->capture_default_str();
    terrain->add_option("--out", terrain_out, "PLY file")->required();
    bool terrain_rough = false;
    terrain->add_flag("--rough", terrain_rough,
                      "The rough terrain (240 x 240 m, facets and roughness to 0.4 m) of the rough scene");
    std::string report_in, report_out;
    int sensor_repeats = 21, multipath_repeats = 7;
    CLI::App* multipath = app.add_subcommand(
        "multipath", "Cost of sampling.bounces 0, 1, 2 on the tank and the wreck (median)");
    multipath->add_option("--repeats", multipath_repeats, "Repeats")->capture_default_str();
    std::vector<std::string> multipath_settings;
    multipath->add_option(
        "--set", multipath_settings,
        "Override a parameter of every case, e.g. --set sampling.estimate=strict (repeatable)");
    CLI::App* sensor = app.add_subcommand("sensor", "Time the sensor stage alone (median of repeats)");
    sensor->add_option("--repeats", sensor_repeats, "Repeats")->capture_default_str();
    std::string sensor_case;
    sensor->add_option("--case", sensor_case, "Only the cases whose name contains this text");
    int devices_repeats = 5;
    CLI::App* devices = app.add_subcommand(
        "devices",
        "Every device preset at its own window over the terrain and the wreck: warm image against the "
        "device's frame interval (median)");
    devices->add_option("--repeats", devices_repeats, "Repeats")->capture_default_str();
    std::vector<std::string> devices_only;
    devices->add_option("--only", devices_only, "Only these presets (default: every one)");
    std::vector<std::string> devices_settings;
    std::string devices_json;
    devices->add_option("--json", devices_json, "Also write the rows as JSON to this file");
    devices->add_option(
        "--set", devices_settings,
        "Override a parameter of every row after its preset, e.g. --set sampling.estimate=strict "
        "(repeatable)");
    int warm_repeats = 9;
    std::vector<std::string> warm_scenes, warm_settings;
    CLI::App* warm = app.add_subcommand(
        "warm",
        "Warm image of scene files (median), rays, the sampler's estimate and the floor, one line each");
    warm->add_option("scenes", warm_scenes, "Scene files")->required();
    warm->add_option("--repeats", warm_repeats, "Repeats")->capture_default_str();
    warm->add_option("--set", warm_settings, "Override a parameter of every scene (repeatable)");
    int slider_repeats = 21;
    std::vector<std::string> slider_scenes;
    CLI::App* slider = app.add_subcommand(
        "slider",
        "Drag each physics slider over scene files: preview time (median), rays traced, full image");
    slider->add_option("scenes", slider_scenes, "Scene files")->required();
    slider->add_option("--repeats", slider_repeats, "Repeats")->capture_default_str();
    CLI::App* report = app.add_subcommand("report", "Rewrite RESULTS.md and results.csv from a results.json");
    report->add_option("results_json", report_in)->required();
    report->add_option("--out", report_out, "Directory (default: the JSON's)");
    CLI11_PARSE(app, argc, argv);
    // bench/run.sh names itself and its arguments; otherwise the command line as given.
    const char* via = std::getenv("SONARSIM_BENCH_COMMAND");
    o.command = via ? std::string(via)
                    : "sonarsim_bench" + std::string(argc > 1 ? " " : "") +
                          quoted(std::vector<std::string>(argv + 1, argv + argc));

    try {
        if (*worker) return run_worker(w);
        if (*report) {
            if (report_out.empty()) report_out = fs::path(report_in).parent_path().string();
            if (report_out.empty()) report_out = ".";
            json in = json::parse(read_text(report_in));
            for (json& sc : in["scenes"]) sc.erase("summary");
            write_reports(in, report_out);
            std::cout << "wrote " << report_out << "/RESULTS.md, results.csv, results.json\n";
            return 0;
        }
        if (*sensor) return run_sensor_bench(sensor_repeats, sensor_case);
        if (*multipath) return run_multipath_bench(o.paths.repo, multipath_repeats, multipath_settings);
        if (*warm) return run_warm_bench(warm_scenes, warm_repeats, warm_settings);
        if (*slider) return run_slider_bench(slider_scenes, slider_repeats);
        if (*devices)
            return run_devices_bench(o.paths, devices_repeats, devices_only, devices_settings, devices_json);
        if (*terrain) {
            write_terrain_ply(terrain_out, grid, terrain_rough);
            std::cout << "wrote " << terrain_out << " (" << terrain_triangles(grid) << " triangles)\n";
            return 0;
        }
        o.paths.repo = fs::absolute(o.paths.repo).lexically_normal().string();
        o.paths.work = fs::absolute(o.paths.work).lexically_normal().string();
        if (o.paths.shared.empty())
            o.paths.shared = (fs::path(o.paths.repo) / ".." / "shared").lexically_normal().string();
        if (o.out.empty())
            o.out = o.quick ? o.paths.work + "/quick-results" : o.paths.repo + "/bench/results";
        return run_driver(o);
    } catch (const sonarsim::InputError& e) { // bad input (a --set, a scene file): exit status 2
        std::cerr << "sonarsim_bench: error: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "sonarsim_bench: error: " << e.what() << "\n";
        return 1;
    }
}

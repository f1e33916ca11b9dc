// `sonarsim_bench devices`: every device preset at its own range window, over the 200 k-triangle terrain and
// over the wreck. Per row: the warm image (a pose change, every stage rerun: trace, shade, sensor, display;
// median of repeats), its rays, its error against a dense reference (rel L1 and median |dB| of the ideal
// image; holes), the *floor* (the same number of rays traced and shaded as a plain beam-ordered grid) and
// the device's own frame interval, which a live simulation has to beat.
//
// Device frame interval: a single-ping sonar cannot image faster than the echo from range_max returns,
// 2 r_max / c. An ARIS frame is fired as sonar.pings_per_frame pings [SENSORS.md 1.2, Reorder.cpp], each
// taking the echo time plus 420 us of overhead, at most 15 fps (FrameRate.cpp, anti-aliasing delay left out).
// DIDSON: at most 21 fps, its pings per frame not being in our sources, so 2 r_max / c is a lower bound
// there.
//
// Scenes, scaled to each device's window so that it sees something: the terrain (bench/terrain.cpp) scaled
// uniformly by r_max / 20 m (relief by at most 2), the sonar pitched 15 deg down with the fan's centre
// meeting the terrain's centre at mid-window; the wreck (assets/scenes/shipwreck.json) seen along the scene's
// own line of sight from mid-window.
#include "bench.hpp"

#include "bench/terrain.hpp"
#include "core/analysis/reference.hpp"
#include "core/data/pose.hpp"
#include "core/grid/sonar_grid.hpp"
#include "core/scene/devices.hpp"
#include "core/io/output.hpp"
#include "core/pipeline/simulator.hpp"
#include "core/sampling/acquisition.hpp"
#include "core/scene/params.hpp"
#include "core/scene/sampling_scheme.hpp"
#include "core/scene/scene_io.hpp"
#include "core/shading/physics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

namespace sonarsim::bench {
namespace {

constexpr double kPitchDeg = 15; // the terrain case's look-down angle

struct Interval {
    double ms;
    const char* how;
};

/// The device's own time per frame (see the file comment).
Interval device_interval(const std::string& name, const SceneDesc& s) {
    const double c = sound_speed_m_s(s.water.temperature_c, s.water.depth_m);
    const double echo_s = 2 * s.sonar.range_max_m / c;
    if (name.rfind("aris", 0) == 0)
        return {1e3 * std::max(1.0 / 15, s.sonar.pings_per_frame * ping_interval_s(s.sonar, c)),
                "pings x (2R/c + 0.42 ms), <= 15 fps"};
    if (name.rfind("didson", 0) == 0) return {1e3 * std::max(1.0 / 21, echo_s), ">= 2R/c, <= 21 fps"};
    return {1e3 * echo_s, "2R/c"};
}

/// Unit vector the sonar looks along (its x axis in the world).
glm::dvec3 forward_of(const SceneDesc& s) {
    return rotation_matrix(s.sonar.pose.orientation_deg) * glm::dvec3(1, 0, 0);
}

void place(SceneDesc& s, const glm::dvec3& aim, double r) {
    const glm::dvec3 p = aim - r * forward_of(s);
    s.sonar.pose.position_m = {p.x, p.y, p.z};
}

SceneDesc terrain_case(const std::string& mesh, const std::string& device) {
    SceneDesc s = default_scene();
    s.seafloor.reset();
    apply_setting(s, "sonar.device", device, "bench");
    apply_setting(s, "sensor.model", "device", "bench");
    const double k = s.sonar.range_max_m / 20, kz = std::min(k, 2.0);
    ObjectDesc o;
    o.mesh = o.mesh_resolved = std::filesystem::absolute(mesh).string();
    o.scale = {k, k, kz};
    s.objects = {o};
    s.sonar.pose.orientation_deg = {0, kPitchDeg, 0};
    place(s, {0, 0, kz * terrain_height_m(0, 0)}, sonar_grid(s.sonar)->window_middle_m());
    // Keep the sonar at least a metre above the ground below it.
    auto& z = s.sonar.pose.position_m[2];
    z = std::max(z,
                 kz * terrain_height_m(s.sonar.pose.position_m[0] / k, s.sonar.pose.position_m[1] / k) + 1);
    return s;
}

SceneDesc wreck_case(const std::string& repo, const std::string& device) {
    SceneDesc s = load_scene(repo + "/assets/scenes/shipwreck.json");
    const glm::dvec3 p0 = to_glm(s.sonar.pose.position_m), f = forward_of(s);
    const glm::dvec3 aim = p0 + (-p0.y / f.y) * f; // where the scene's line of sight crosses the keel line
    // The scene sets its own sonar; the preset's values go over them, as a user's `--set sonar.device` does.
    apply_setting(s, "sonar.device", device, "bench");
    apply_setting(s, "sensor.model", "device", "bench");
    place(s, aim, sonar_grid(s.sonar)->window_middle_m());
    return s;
}

struct Row {
    double warm_ms = 0, floor_ms = 0, interval_ms = 0;
    double est_rel_l1 = 0; ///< the sampler's own estimate (0: none)
    std::uint64_t rays = 0;
    ImageError err;
    const char* interval_how = "";
};

Row measure(SceneDesc s, const std::string& device, int repeats) {
    Row row;
    Simulator sim(s);
    std::shared_ptr<const Frame> f;
    row.warm_ms = warm_ms(sim, s, repeats, &f);
    row.rays = f->hits().rays_traced;
    if (f->error_estimate.valid) row.est_rel_l1 = f->error_estimate.rel_l1;
    const Interval iv = device_interval(device, s);
    row.interval_ms = iv.ms, row.interval_how = iv.how;

    // The reference: the last frame's pose, the ideal sensor, a dense spread grid.
    SceneDesc ref = s;
    ref.sonar.pose.orientation_deg[2] = s.sonar.pose.orientation_deg[2] + 0.01 * repeats;
    row.err = error_against_reference(*f, ref);

    row.floor_ms = floor_ms(s, row.rays, repeats);
    return row;
}

} // namespace

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

/// Median over `repeats` renders of `s`, the yaw nudged each time so that every stage reruns; `last` keeps
/// the last frame.
double warm_ms(Simulator& sim, SceneDesc s, int repeats, std::shared_ptr<const Frame>* last) {
    const double yaw0 = s.sonar.pose.orientation_deg[2];
    sim.set_scene(s);
    sim.render(); // the BVH, the resampler and the caches: not part of a warm image
    std::vector<double> ms;
    for (int i = 1; i <= repeats; ++i) {
        s.sonar.pose.orientation_deg[2] = yaw0 + 0.01 * i;
        sim.set_scene(s);
        const auto f = sim.render();
        ms.push_back(f->trace_ms + f->shade_ms + f->sensor_ms + f->image_ms);
        if (last) *last = f;
    }
    return median(ms);
}

double floor_ms(const SceneDesc& s, std::uint64_t rays, int repeats) {
    SceneDesc grid = floor_grid(s, rays);
    Simulator floor_sim(grid);
    std::vector<double> ms;
    floor_sim.render();
    const double yaw0 = grid.sonar.pose.orientation_deg[2];
    for (int i = 1; i <= repeats; ++i) {
        grid.sonar.pose.orientation_deg[2] = yaw0 + 0.01 * i;
        floor_sim.set_scene(grid);
        const auto g = floor_sim.render();
        ms.push_back(g->trace_ms + g->shade_ms);
    }
    return median(ms);
}

SceneDesc floor_grid(SceneDesc s, std::uint64_t rays) {
    set_scheme(s.sampling, SamplingScheme::Spread);
    s.sampling.azimuth_rays = 1;
    s.sampling.elevation_rays =
        int(std::max<std::uint64_t>(1, rays / std::uint64_t(std::max(1, s.sonar.beams))));
    return s;
}

ImageError error_against_reference(const Frame& f, SceneDesc at_pose) {
    set_scheme(at_pose.sampling, SamplingScheme::Spread);
    at_pose.sampling.elevation_rays = kReferenceRays, at_pose.sampling.azimuth_rays = kReferenceColumns;
    return compare_images(f.ideal(), Simulator(at_pose).render()->ideal());
}

std::string devices_table_header() {
    return "| device | scene | beams x bins | range m | rays | warm ms | floor ms | warm / floor | rel L1 % "
           "| "
           "median dB | holes % | estimate rel L1 % | device frame ms | live |\n"
           "|---|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n";
}

std::string devices_table_row(const json& r) {
    auto num = [&](const char* k) { return r.at(k).get<double>(); };
    char b[512];
    std::snprintf(
        b, sizeof b,
        "| %s | %s | %d x %d | %g-%g | %llu | %.1f | %.1f | %.1f | %.2f | %.3f | %.2f | %.2f | %.0f (%s) "
        "| %s |\n",
        r.at("device").get<std::string>().c_str(), r.at("scene").get<std::string>().c_str(),
        r.at("beams").get<int>(), r.at("range_bins").get<int>(), num("range_min_m"), num("range_max_m"),
        (unsigned long long)r.at("rays").get<std::uint64_t>(), num("warm_ms"), num("floor_ms"),
        num("warm_ms") / num("floor_ms"), 100 * num("rel_l1"), num("median_abs_db"), 100 * num("holes_share"),
        100 * num("estimate_rel_l1"), num("device_frame_ms"),
        r.at("device_frame_how").get<std::string>().c_str(), r.at("live").get<bool>() ? "yes" : "no");
    return b;
}

std::string devices_table_summary(const json& rows) {
    int live = 0;
    for (const json& r : rows) live += r.at("live").get<bool>();
    return std::to_string(live) + " of " + std::to_string(rows.size()) +
           " rows live: warm image shorter than the device's frame and at most 50 ms.\n";
}

int run_devices_bench(const Paths& p, int repeats, const std::vector<std::string>& only,
                      const std::vector<std::string>& settings, const std::string& json_out) {
    const std::string work = p.work.empty() ? "build/bench" : p.work;
    std::filesystem::create_directories(work);
    const std::string mesh = work + "/terrain_317.ply";
    if (!std::filesystem::exists(mesh)) write_terrain_ply(mesh, 317);
    std::printf("Every device preset at its own window (sensor.model device, default sampling), warm image: "
                "median of %d; reference: spread %d x %d, ideal sensor\n\n",
                repeats, kReferenceRays, kReferenceColumns);
    for (const auto& a : settings) std::printf("--set %s\n", a.c_str());
    std::printf("%s", devices_table_header().c_str());
    std::fflush(stdout);
    json rows = json::array();
    for (const DevicePreset& d : device_presets())
        for (int scene = 0; scene < 2; ++scene) {
            if (!only.empty() && std::find(only.begin(), only.end(), d.name) == only.end()) continue;
            status_line("devices: " + d.name + (scene ? ", wreck" : ", terrain"));
            SceneDesc s = scene ? wreck_case(p.repo, d.name) : terrain_case(mesh, d.name);
            for (const auto& a : settings) apply_setting_text(s, a, "--set");
            const Row r = measure(s, d.name, repeats);
            const json row = {
                {"device", d.name},
                {"scene", scene ? "wreck" : "terrain"},
                {"beams", s.sonar.beams},
                {"range_bins", s.sonar.range_bins},
                {"range_min_m", s.sonar.range_min_m},
                {"range_max_m", s.sonar.range_max_m},
                {"rays", r.rays},
                {"warm_ms", r.warm_ms},
                {"floor_ms", r.floor_ms},
                {"rel_l1", r.err.rel_l1},
                {"median_abs_db", r.err.median_abs_db},
                {"holes_share", r.err.echoing_ref ? double(r.err.holes) / double(r.err.echoing_ref) : 0.0},
                {"estimate_rel_l1", r.est_rel_l1},
                {"device_frame_ms", r.interval_ms},
                {"device_frame_how", r.interval_how},
                {"live", r.warm_ms < r.interval_ms && r.warm_ms <= 50},
            };
            rows.push_back(row);
            status_line("");
            std::printf("%s", devices_table_row(row).c_str());
            std::fflush(stdout);
        }
    std::printf("\n%s", devices_table_summary(rows).c_str());
    if (!json_out.empty()) {
        const json out = {{"repeats", repeats}, {"settings", settings}, {"rows", rows}};
        write_files_atomically({{json_out, to_bytes(out.dump(1) + "\n")}});
    }
    return 0;
}

} // namespace sonarsim::bench

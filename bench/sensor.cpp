// `sonarsim_bench sensor`: the sensor stage alone, timed on the two sizes the targets name (128 beams x 512
// bins: the ARIS 3000 on the Fig. 9 scene; 512 x 1500: an Oculus-class wide sonar over a floor, and the
// oculus-m750d-lf preset with its own wide pattern over the same floor), with every effect of the device
// sensor on. Only sensor.seed changes between repeats, so each render runs the
// sensor stage and the display, nothing before them.
#include "bench.hpp"

#include "core/scene/params.hpp"
#include "core/scene/scene_io.hpp"
#include "core/pipeline/simulator.hpp"

#include <algorithm>
#include <sys/resource.h>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <iostream>

namespace sonarsim::bench {

namespace {

/// CPU time of this process so far, all threads [ms]: unlike wall time, it does not grow when other
/// processes share the cores.
double cpu_ms() {
    rusage ru{};
    getrusage(RUSAGE_SELF, &ru);
    return (ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) * 1e3 +
           (ru.ru_utime.tv_usec + ru.ru_stime.tv_usec) / 1e3;
}

} // namespace

int run_sensor_bench(int repeats, const std::string& only) {
    struct Case {
        std::string name;
        SceneDesc scene;
    };
    std::vector<Case> cases;
    SceneDesc aris = default_scene();
    apply_setting(aris, "sensor.model", "device", "bench");
    apply_setting(aris, "sensor.range_resolution_m", 0.0075, "bench"); // c tau / 2 of a 10 us pulse
    cases.push_back({"ARIS 3000, 128 x 512, Fig. 9 scene", aris});
    SceneDesc wide = default_scene();
    wide.objects.clear();
    wide.sonar.azimuth_fov_deg = 130, wide.sonar.elevation_fov_deg = 20, wide.sonar.beams = 512;
    wide.sonar.range_min_m = 0.5, wide.sonar.range_max_m = 120, wide.sonar.range_bins = 1500;
    wide.sonar.frequency_khz = 750;
    wide.sonar.pose.position_m = {0, 0, 10}, wide.sonar.pose.orientation_deg = {0, 10, 0};
    apply_setting(wide, "sensor.model", "device", "bench");
    apply_setting(wide, "sensor.azimuth_beamwidth_deg", 1.0, "bench");
    apply_setting(wide, "sensor.beamformer", "array", "bench");
    apply_setting(wide, "sensor.range_resolution_m", 0.2, "bench");
    cases.push_back({"Oculus-class, 512 x 1500, floor", wide});
    // A wide preset with its own pattern (Taylor -30 dB, 1 deg at broadside widening off it, two fine columns
    // per beam), its own range window and speckle, over the same floor; only the bins set to 1500.
    SceneDesc preset = default_scene();
    preset.objects.clear();
    apply_setting(preset, "sonar.device", "oculus-m750d-lf", "bench");
    apply_setting(preset, "sensor.model", "device", "bench");
    apply_setting(preset, "sonar.range_bins", 1500, "bench");
    preset.sonar.pose.position_m = {0, 0, 10}, preset.sonar.pose.orientation_deg = {0, 10, 0};
    cases.push_back({"oculus-m750d-lf, 512 x 1500, floor", preset});
    for (int variant = 0; variant < 2; ++variant)
        for (auto& c : cases) {
            if (c.name.find(only) == std::string::npos) continue;
            SceneDesc s = c.scene;
            if (variant == 1) apply_setting(s, "sensor.speckle", "k", "bench");
            Simulator sim(s);
            sim.render();
            std::vector<double> ms, cpu;
            std::uint64_t hash =
                0xcbf29ce484222325ULL; // FNV-1a of the last image's levels: same bits, same hash
            for (int i = 0; i < repeats; ++i) {
                s.sensor.seed = i + 2;
                sim.set_scene(s);
                const double c0 = cpu_ms();
                const auto f = sim.render();
                cpu.push_back(cpu_ms() - c0);
                ms.push_back(f->sensor_ms);
                if (i + 1 == repeats)
                    for (const float v : f->polar().level_db) {
                        unsigned char b[sizeof v];
                        std::memcpy(b, &v, sizeof v);
                        for (const unsigned char c : b) hash = (hash ^ c) * 0x100000001b3ULL;
                    }
            }
            std::sort(ms.begin(), ms.end());
            std::sort(cpu.begin(), cpu.end());
            std::printf("%-36s speckle %-8s sensor stage: median %.2f ms wall (min %.2f, max %.2f); sensor + "
                        "display %.1f ms CPU (all threads); %d repeats; image %016llx\n",
                        c.name.c_str(), variant ? "k" : "rayleigh", ms[ms.size() / 2], ms.front(), ms.back(),
                        cpu[cpu.size() / 2], repeats, (unsigned long long)hash);
        }
    return 0;
}

} // namespace sonarsim::bench

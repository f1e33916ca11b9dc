#include "ui/model/param_ranges.hpp"

#include <algorithm>
#include <map>

namespace sonarsim::ui {

SliderRange slider_range(const ValueSpec& spec) {
    static const std::map<std::string, SliderRange> table = {
        {"sonar.frequency_khz", {100, 5000, true}},
        {"sonar.azimuth_fov_deg", {2, 130, false}},
        {"sonar.elevation_fov_deg", {1, 60, false}},
        {"sonar.beams", {8, 512, true}},
        {"sonar.range_min_m", {0, 10, false}},
        {"sonar.range_max_m", {0.5, 40, true}},
        {"sonar.range_bins", {32, 2048, true}},
        {"sonar.source_level_db", {150, 250, false}},
        {"sonar.noise_level_db", {-40, 100, false}},
        {"water.temperature_c", {-2, 40, false}},
        {"water.depth_m", {0, 6000, false}},
        {"water.surface_height_m", {-10, 20, false}},
        {"water.surface_roughness_m", {0, 0.005, false}},
        {"reflection_db", {0, 40, false}},
        {"sampling.elevation_rays", {1, 2000, true}},
        {"sampling.azimuth_rays", {1, 16, false}},
        {"sampling.tolerance_db", {0.01, 3, true}},
        {"display.lo_db", {-50, 200, false}},
        {"sensor.azimuth_beamwidth_deg", {0, 5, false}},
        {"sensor.taylor_sidelobe_db", {-60, -20, false}},
        {"sensor.elevation_beamwidth_deg", {0, 40, false}},
        {"sensor.range_resolution_m", {0, 0.2, false}},
        {"sensor.speckle_k_shape", {0.3, 50, true}},
        {"sensor.seed", {0, 1000, false}},
        {"sensor.gain_db", {-40, 40, false}},
        {"display.hi_db", {-50, 250, false}},
        {"nu_db", {-90, 0, false}},
        {"q", {0, 20, false}},
        {"mu", {0, 10, false}},
        {"h_deg", {0.5, 45, false}},
        {"texture_rms_db", {0, 8, false}},
        {"texture_correlation_m", {0.02, 20, true}},
        {"ripple_amplitude_db", {0, 6, false}},
        {"ripple_wavelength_m", {0.05, 5, true}},
        {"ripple_direction_deg", {-180, 180, false}},
        {"slope_rms_deg", {0, 20, false}},
    };
    SliderRange r{spec.min, spec.max, false};
    if (auto it = table.find(spec.key); it != table.end()) r = it->second;
    r.lo = std::max(r.lo, spec.min), r.hi = std::min(r.hi, spec.max);
    if (r.logarithmic && r.lo <= 0) r.logarithmic = false;
    return r;
}

std::string param_section(const ParamSpec& spec) {
    if (spec.type == ParamType::Vec3) return "Pose";
    const std::string head = spec.key.substr(0, spec.key.find('.'));
    if (head == "sonar") return "Sonar";
    if (head == "water") return "Water";
    if (head == "sampling") return "Sampling";
    if (head == "display") return "Display";
    if (head == "sensor") return "Sensor";
    return head;
}

std::string param_label(const ValueSpec& spec) {
    static const std::map<std::string, std::string> names = {{"sonar.frequency_khz", "f frequency"},
                                                             {"sonar.source_level_db", "L_S source level"},
                                                             {"sonar.noise_level_db", "L_N noise level"},
                                                             {"water.temperature_c", "T temperature"},
                                                             {"water.depth_m", "D depth"},
                                                             {"nu_db", "10 log nu"},
                                                             {"h_deg", "h lobe width"},
                                                             {"q", "q exponent"},
                                                             {"mu", "mu specular"},
                                                             {"sonar.azimuth_fov_deg", "azimuth FOV"},
                                                             {"sonar.elevation_fov_deg", "elevation FOV"},
                                                             {"display.lo_db", "lo (black)"},
                                                             {"display.hi_db", "hi (white)"}};
    std::string name;
    if (auto it = names.find(spec.key); it != names.end()) {
        name = it->second;
    } else {
        const size_t dot = spec.key.find('.');
        name = dot == std::string::npos ? spec.key : spec.key.substr(dot + 1);
        for (const char* suffix : {"_khz", "_deg", "_db", "_m", "_c"}) {
            const std::string x(suffix);
            if (name.size() > x.size() && name.compare(name.size() - x.size(), x.size(), x) == 0) {
                name.resize(name.size() - x.size());
                break;
            }
        }
        std::replace(name.begin(), name.end(), '_', ' ');
    }
    return spec.unit.empty() ? name : name + " [" + spec.unit + "]";
}

} // namespace sonarsim::ui

// The sensor's rows of the parameter table: the model (ideal or device) and each effect a device has on
// the ideal image (sensor/sensor.hpp). Rows with an ideal value (sensor_values) are the effect switches
// that sensor.model sets.
#include "core/scene/param_rows.hpp"

namespace sonarsim::rows {

std::vector<ParamSpec> sensor_rows() {
    std::vector<ParamSpec> t;
    t.push_back(enumeration<SensorModel>(
        "sensor.model", {"ideal", "device"}, Stage::None,
        "ideal: the echo image as the sampler converges it; device: every effect the device preset (or, "
        "without one, the generic device) defines, on. Sensor keys given in the scene override it",
        [](S s) -> SensorModel& { return s.sensor.model; }));
    t.push_back(
        enumeration<AzimuthWindow>("sensor.azimuth_window", {"none", "rect", "hann", "taylor"}, Stage::Shade,
                                   "Receive beam pattern in azimuth: the array factor of a line array "
                                   "with this window (rect: first sidelobe -13.3 dB); none: each beam "
                                   "is a hard slice",
                                   [](S s) -> AzimuthWindow& { return s.sensor.azimuth_window; })
            .sensor_values("none", "hann")
            .preset()
            .only_for({SonarKind::Imaging}));
    t.push_back(number("sensor.azimuth_beamwidth_deg", "deg", 0, 180, false, true, Stage::Shade,
                       "-3 dB width of the receive beam at broadside; 0: the beam spacing",
                       [](S s) -> double& { return s.sensor.azimuth_beamwidth_deg; })
                    .preset()
                    .only_for({SonarKind::Imaging})
                    .with_slider(0, 5));
    t.push_back(number("sensor.taylor_sidelobe_db", "dB", -80, -13.3, false, false, Stage::Sensor,
                       "Design sidelobe level of the taylor window",
                       [](S s) -> double& { return s.sensor.taylor_sidelobe_db; })
                    .preset()
                    .only_for({SonarKind::Imaging})
                    .with_slider(-60, -20));
    t.push_back(enumeration<Beamformer>("sensor.beamformer", {"lens", "array"}, Stage::Sensor,
                                        "lens: every beam has the broadside width (ARIS, DIDSON); array: a "
                                        "flat receive array, whose beams widen as 1 / cos(azimuth) off "
                                        "broadside",
                                        [](S s) -> Beamformer& { return s.sensor.beamformer; })
                    .preset()
                    .only_for({SonarKind::Imaging}));
    t.push_back(
        enumeration<ElevationPattern>(
            "sensor.elevation_pattern", {"flat", "gaussian", "sinc"}, Stage::Trace,
            "Two-way elevation pattern weighting each ray: flat is the hard aperture; gaussian and sinc^2 "
            "are smooth, traced out to -30 dB (gaussian) or their second null (sinc)",
            [](S s) -> ElevationPattern& { return s.sensor.elevation_pattern; })
            .sensor_values("flat", "gaussian")
            .preset());
    t.push_back(number("sensor.elevation_beamwidth_deg", "deg", 0, 60, false, false, Stage::Trace,
                       "-3 dB width of the two-way elevation pattern; 0: sonar.elevation_fov_deg",
                       [](S s) -> double& { return s.sensor.elevation_beamwidth_deg; })
                    .preset()
                    .with_slider(0, 40));
    t.push_back(number("sensor.range_resolution_m", "m", 0, 100, false, false, Stage::Sensor,
                       "Range resolution of the matched filter: c tau / 2 (cw) or c / 2B (chirp); 0: ideal",
                       [](S s) -> double& { return s.sensor.range_resolution_m; })
                    .sensor_values(0.0, nullptr)
                    .preset()
                    .with_slider(0, 0.2));
    t.push_back(
        enumeration<Pulse>("sensor.pulse", {"cw", "chirp"}, Stage::Sensor,
                           "Pulse: cw (matched-filter intensity response a squared triangle) or chirp "
                           "(sinc^2)",
                           [](S s) -> Pulse& { return s.sensor.pulse; })
            .preset());
    t.push_back(enumeration<Speckle>("sensor.speckle", {"off", "rayleigh", "k"}, Stage::Shade,
                                     "Speckle per resolution cell: rayleigh (exponential intensity) or k "
                                     "(K-distributed); anchored to the scatterers in the world",
                                     [](S s) -> Speckle& { return s.sensor.speckle; })
                    .sensor_values("off", "rayleigh")
                    .preset());
    t.push_back(number("sensor.speckle_k_shape", "", 0, 1e6, true, false, Stage::Sensor,
                       "K-distribution shape alpha: scintillation index 1 + 2 / alpha",
                       [](S s) -> double& { return s.sensor.speckle_k_shape; })
                    .preset()
                    .with_log_slider(0.3, 50));
    t.push_back(
        integer("sensor.seed", 0, 2147483647, Stage::Sensor, "Seed of speckle and noise", [](S s) -> int& {
            return s.sensor.seed;
        }).with_slider(0, 1000));
    t.push_back(boolean("sensor.noise", Stage::Sensor,
                        "Additive complex Gaussian noise at the noise level L_N (before gain)",
                        [](S s) -> bool& { return s.sensor.noise; })
                    .sensor_values(false, true)
                    .preset());
    t.push_back(enumeration<Tvg>("sensor.tvg", {"off", "20log", "30log", "40log"}, Stage::Sensor,
                                 "Time-varying gain: N log10 R + 2 alpha R [dB]",
                                 [](S s) -> Tvg& { return s.sensor.tvg; })
                    .sensor_values("off", "30log")
                    .preset());
    t.push_back(number("sensor.gain_db", "dB", -200, 200, false, false, Stage::Sensor,
                       "Receiver gain added to the output level",
                       [](S s) -> double& { return s.sensor.gain_db; })
                    .sensor_values(0.0, nullptr)
                    .preset()
                    .with_slider(-40, 40));
    return t;
}

} // namespace sonarsim::rows

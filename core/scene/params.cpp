#include "core/scene/params.hpp"

#include "core/scene/sampling_scheme.hpp"

#include "core/devices/devices.hpp"
#include "core/geometry/mesh_formats.hpp"
#include "core/base/errors.hpp"
#include "core/base/pose.hpp"
#include "core/sensor/sensor_patterns.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>
#include <stdexcept>
#include <sstream>

namespace sonarsim {
namespace {

std::string fmt(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

ParamSpec number(std::string key, std::string unit, double lo, double hi, bool lo_ex, bool hi_ex, Stage stage,
                 std::string help, std::function<double&(SceneDesc&)> ref) {
    ParamSpec p;
    p.key = std::move(key);
    p.unit = std::move(unit);
    p.type = ParamType::Number;
    p.min = lo;
    p.max = hi;
    p.min_exclusive = lo_ex;
    p.max_exclusive = hi_ex;
    p.stage = stage;
    p.help = std::move(help);
    p.get = [ref](const SceneDesc& s) { return json(ref(const_cast<SceneDesc&>(s))); };
    p.put = [ref](SceneDesc& s, const json& v) { ref(s) = v.get<double>(); };
    return p;
}

/// A number that may be absent (null): std::optional in the scene.
ParamSpec optional_number(std::string key, std::string unit, double lo, double hi, Stage stage,
                          std::string help, std::function<std::optional<double>&(SceneDesc&)> ref) {
    ParamSpec p = number(std::move(key), std::move(unit), lo, hi, false, false, stage, std::move(help),
                         [](SceneDesc&) -> double& { throw std::logic_error("optional"); });
    p.optional = true;
    p.get = [ref](const SceneDesc& s) {
        const auto& v = ref(const_cast<SceneDesc&>(s));
        return v ? json(*v) : json(nullptr);
    };
    p.put = [ref](SceneDesc& s, const json& v) {
        ref(s) = v.is_null() ? std::nullopt : std::optional<double>(v.get<double>());
    };
    return p;
}

ParamSpec integer(std::string key, double lo, double hi, Stage stage, std::string help,
                  std::function<int&(SceneDesc&)> ref) {
    ParamSpec p;
    p.key = std::move(key);
    p.type = ParamType::Integer;
    p.min = lo;
    p.max = hi;
    p.stage = stage;
    p.help = std::move(help);
    p.get = [ref](const SceneDesc& s) { return json(ref(const_cast<SceneDesc&>(s))); };
    p.put = [ref](SceneDesc& s, const json& v) { ref(s) = v.get<int>(); };
    return p;
}

ParamSpec vec3(std::string key, std::string unit, double lo, double hi, Stage stage, std::string help,
               std::function<Vec3d&(SceneDesc&)> ref) {
    ParamSpec p;
    p.key = std::move(key);
    p.unit = std::move(unit);
    p.type = ParamType::Vec3;
    p.min = lo;
    p.max = hi;
    p.stage = stage;
    p.help = std::move(help);
    p.get = [ref](const SceneDesc& s) { return json(ref(const_cast<SceneDesc&>(s))); };
    p.put = [ref](SceneDesc& s, const json& v) { ref(s) = v.get<Vec3d>(); };
    return p;
}

template <class E>
ParamSpec enumeration(std::string key, std::vector<std::string> choices, Stage stage, std::string help,
                      std::function<E&(SceneDesc&)> ref) {
    ParamSpec p;
    p.key = std::move(key);
    p.type = ParamType::Enum;
    p.choices = std::move(choices);
    p.stage = stage;
    p.help = std::move(help);
    auto names = p.choices;
    p.get = [ref, names](const SceneDesc& s) {
        return json(names.at(size_t(ref(const_cast<SceneDesc&>(s)))));
    };
    p.put = [ref, names](SceneDesc& s, const json& v) {
        for (size_t i = 0; i < names.size(); ++i)
            if (names[i] == v.get<std::string>()) ref(s) = E(i);
    };
    return p;
}

ParamSpec boolean(std::string key, Stage stage, std::string help, std::function<bool&(SceneDesc&)> ref) {
    ParamSpec p;
    p.key = std::move(key);
    p.type = ParamType::Bool;
    p.stage = stage;
    p.help = std::move(help);
    p.get = [ref](const SceneDesc& s) { return json(ref(const_cast<SceneDesc&>(s))); };
    p.put = [ref](SceneDesc& s, const json& v) { ref(s) = v.get<bool>(); };
    return p;
}

/// A sensor row: `ideal` is what sensor.model "ideal" sets, `device` what "device" sets where the preset
/// says nothing (null: the model leaves the value alone).
/// A row the adaptive sampler steers by (ValueSpec::steers_sampler).
ParamSpec steers(ParamSpec p) {
    p.steers_sampler = true;
    return p;
}

ParamSpec sensor(ParamSpec p, json ideal, json device) {
    p.ideal_value = std::move(ideal);
    p.device_value = std::move(device);
    return p;
}

MaterialSpec material(std::string key, std::string unit, double lo, double hi, bool lo_ex, std::string help,
                      double Material::*field) {
    MaterialSpec m;
    m.key = std::move(key);
    m.unit = std::move(unit);
    m.type = ParamType::Number;
    m.min = lo;
    m.max = hi;
    m.min_exclusive = lo_ex;
    m.stage = Stage::Shade;
    m.steers_sampler = true; // a material's level and lobe decide where the adaptive sampler refines
    m.help = std::move(help);
    m.field = field;
    return m;
}

void add_sensor_params(std::vector<ParamSpec>& t) {
    using S = SceneDesc&;
    t.push_back(enumeration<SensorModel>(
        "sensor.model", {"ideal", "device"}, Stage::None,
        "ideal: the echo image as the sampler converges it; device: every effect the device preset (or, "
        "without one, the generic device) defines, on. Sensor keys given in the scene override it",
        [](S s) -> SensorModel& { return s.sensor.model; }));
    t.push_back(sensor(enumeration<AzimuthWindow>(
                           "sensor.azimuth_window", {"none", "rect", "hann", "taylor"}, Stage::Shade,
                           "Receive beam pattern in azimuth: the array factor of a line array with this "
                           "window (rect: first sidelobe -13.3 dB); none: each beam is a hard slice",
                           [](S s) -> AzimuthWindow& { return s.sensor.azimuth_window; }),
                       "none", "hann"));
    t.push_back(number("sensor.azimuth_beamwidth_deg", "deg", 0, 180, false, true, Stage::Shade,
                       "-3 dB width of the receive beam at broadside; 0: the beam spacing",
                       [](S s) -> double& { return s.sensor.azimuth_beamwidth_deg; }));
    t.push_back(number("sensor.taylor_sidelobe_db", "dB", -80, -13.3, false, false, Stage::Sensor,
                       "Design sidelobe level of the taylor window",
                       [](S s) -> double& { return s.sensor.taylor_sidelobe_db; }));
    t.push_back(enumeration<Beamformer>(
        "sensor.beamformer", {"lens", "array"}, Stage::Sensor,
        "lens: every beam has the broadside width (ARIS, DIDSON); array: a flat receive "
        "array, whose beams widen as 1 / cos(azimuth) off broadside",
        [](S s) -> Beamformer& { return s.sensor.beamformer; }));
    t.push_back(sensor(enumeration<ElevationPattern>(
                           "sensor.elevation_pattern", {"flat", "gaussian", "sinc"}, Stage::Trace,
                           "Two-way elevation pattern weighting each ray: flat is the hard aperture; "
                           "gaussian and sinc^2 are smooth, traced out to -30 dB (gaussian) or their second "
                           "null (sinc)",
                           [](S s) -> ElevationPattern& { return s.sensor.elevation_pattern; }),
                       "flat", "gaussian"));
    t.push_back(number("sensor.elevation_beamwidth_deg", "deg", 0, 60, false, false, Stage::Trace,
                       "-3 dB width of the two-way elevation pattern; 0: sonar.elevation_fov_deg",
                       [](S s) -> double& { return s.sensor.elevation_beamwidth_deg; }));
    t.push_back(sensor(number("sensor.range_resolution_m", "m", 0, 100, false, false, Stage::Sensor,
                              "Range resolution of the matched filter: c tau / 2 (cw) or c / 2B (chirp); "
                              "0: ideal",
                              [](S s) -> double& { return s.sensor.range_resolution_m; }),
                       0.0, nullptr));
    t.push_back(enumeration<Pulse>("sensor.pulse", {"cw", "chirp"}, Stage::Sensor,
                                   "Pulse: cw (matched-filter intensity response a squared triangle) "
                                   "or chirp (sinc^2)",
                                   [](S s) -> Pulse& { return s.sensor.pulse; }));
    t.push_back(sensor(enumeration<Speckle>("sensor.speckle", {"off", "rayleigh", "k"}, Stage::Shade,
                                            "Speckle per resolution cell: rayleigh (exponential intensity) "
                                            "or k (K-distributed); anchored to the scatterers in the world",
                                            [](S s) -> Speckle& { return s.sensor.speckle; }),
                       "off", "rayleigh"));
    t.push_back(number("sensor.speckle_k_shape", "", 0, 1e6, true, false, Stage::Sensor,
                       "K-distribution shape alpha: scintillation index 1 + 2 / alpha",
                       [](S s) -> double& { return s.sensor.speckle_k_shape; }));
    t.push_back(integer("sensor.seed", 0, 2147483647, Stage::Sensor, "Seed of speckle and noise",
                        [](S s) -> int& { return s.sensor.seed; }));
    t.push_back(sensor(boolean("sensor.noise", Stage::Sensor,
                               "Additive complex Gaussian noise at the noise level L_N (before gain)",
                               [](S s) -> bool& { return s.sensor.noise; }),
                       false, true));
    t.push_back(sensor(enumeration<Tvg>("sensor.tvg", {"off", "20log", "30log", "40log"}, Stage::Sensor,
                                        "Time-varying gain: N log10 R + 2 alpha R [dB]",
                                        [](S s) -> Tvg& { return s.sensor.tvg; }),
                       "off", "30log"));
    t.push_back(sensor(number("sensor.gain_db", "dB", -200, 200, false, false, Stage::Sensor,
                              "Receiver gain added to the output level",
                              [](S s) -> double& { return s.sensor.gain_db; }),
                       0.0, nullptr));
}

std::vector<ParamSpec> build_scene_params() {
    using S = SceneDesc&;
    std::vector<ParamSpec> t;
    ParamSpec device;
    device.key = "sonar.device";
    device.type = ParamType::Enum;
    device.choices = device_choices();
    device.stage = Stage::None; // what it changes is compared key by key
    device.help = "Device preset (assets/devices/NAME.json, `sonarsim devices`): sets the device's values; "
                  "keys given in the scene override them";
    device.get = [](const SceneDesc& s) { return json(s.sonar.device); };
    device.put = [](SceneDesc& s, const json& v) { s.sonar.device = v.get<std::string>(); };
    t.push_back(device);
    t.push_back(vec3("sonar.position", "m", -1e6, 1e6, Stage::Trace, "Sonar position x, y, z (world, z up)",
                     [](S s) -> Vec3d& { return s.sonar.pose.position_m; }));
    t.push_back(vec3("sonar.orientation_deg", "deg", -360, 360, Stage::Trace,
                     "Roll, pitch, yaw; R = Rz(yaw) Ry(pitch) Rx(roll); positive pitch looks down",
                     [](S s) -> Vec3d& { return s.sonar.pose.orientation_deg; }));
    t.push_back(steers(number("sonar.frequency_khz", "kHz", 1, 10000, false, false, Stage::Shade,
                              "Carrier frequency f (absorption, eq. 7)",
                              [](S s) -> double& { return s.sonar.frequency_khz; })));
    t.push_back(number("sonar.azimuth_fov_deg", "deg", 0, 180, true, true, Stage::Trace,
                       "Azimuth field of view Theta",
                       [](S s) -> double& { return s.sonar.azimuth_fov_deg; }));
    t.push_back(number("sonar.elevation_fov_deg", "deg", 0, 180, true, true, Stage::Trace,
                       "Elevation aperture Phi", [](S s) -> double& { return s.sonar.elevation_fov_deg; }));
    t.push_back(integer("sonar.beams", 1, 4096, Stage::Trace, "Number of beams N (eq. 10)",
                        [](S s) -> int& { return s.sonar.beams; }));
    t.push_back(number("sonar.range_min_m", "m", 0, 1000, false, true, Stage::Trace,
                       "Start of the range window r_min",
                       [](S s) -> double& { return s.sonar.range_min_m; }));
    t.push_back(number("sonar.range_max_m", "m", 0, 1000, true, false, Stage::Trace,
                       "End of the range window r_max", [](S s) -> double& { return s.sonar.range_max_m; }));
    t.push_back(integer("sonar.range_bins", 1, 65536, Stage::Trace, "Range bins K over [r_min, r_max)",
                        [](S s) -> int& { return s.sonar.range_bins; }));
    t.push_back(number("sonar.source_level_db", "dB", 0, 300, false, false, Stage::Shade,
                       "Source level L_S (dB re 1 uPa at 1 m)",
                       [](S s) -> double& { return s.sonar.source_level_db; }));
    t.push_back(number("sonar.noise_level_db", "dB", -200, 300, false, false, Stage::Shade, "Noise level L_N",
                       [](S s) -> double& { return s.sonar.noise_level_db; }));
    // Bounds: the absorption formula (Ainslie & McColm 1998) holds for -6 < T < 35 degC and 0 < z < 7 km;
    // below -2 degC sea water is ice.
    t.push_back(steers(number("water.temperature_c", "degC", -2, 35, false, false, Stage::Shade,
                              "Water temperature T (absorption formula range)",
                              [](S s) -> double& { return s.water.temperature_c; })));
    t.push_back(steers(number("water.depth_m", "m", 0, 7000, false, false, Stage::Shade,
                              "Water depth D (absorption)", [](S s) -> double& { return s.water.depth_m; })));
    t.push_back(optional_number("water.surface_height_m", "m", -1e6, 1e6, Stage::Trace,
                                "Multipath: height z of the water surface, a pressure-release mirror that "
                                "also backscatters (water.surface_material); null: no surface",
                                [](S s) -> std::optional<double>& { return s.water.surface_height_m; }));
    t.push_back(
        steers(number("water.surface_roughness_m", "m", 0, 1, false, false, Stage::Shade,
                      "Multipath: rms height sigma of the surface; coherent reflection (energy) R^2 = "
                      "exp(-(2 k sigma cos theta)^2) (Kirchhoff/Eckart; theta from the normal)",
                      [](S s) -> double& { return s.water.surface_roughness_m; })));
    t.push_back(integer("sampling.elevation_rays", 1, 1000000, Stage::Trace, "Elevation rays M per beam",
                        [](S s) -> int& { return s.sampling.elevation_rays; }));
    t.push_back(integer("sampling.azimuth_rays", 1, 1024, Stage::Trace, "Azimuth rays per beam",
                        [](S s) -> int& { return s.sampling.azimuth_rays; }));
    t.push_back(enumeration<NormalSource>(
        "sampling.normals", {"mesh", "paper"}, Stage::Trace,
        "Incidence from the true surface normal, or the paper's neighbour-difference normal (eq. 13-14)",
        [](S s) -> NormalSource& { return s.sampling.normals; }));
    ParamSpec scheme; // a name for the combination of sampling.placement and sampling.binning
    scheme.key = "sampling.scheme";
    scheme.type = ParamType::Enum;
    for (const NamedSampling& n : kSamplingSchemes) scheme.choices.push_back(n.name);
    scheme.stage = Stage::Trace;
    scheme.help =
        "Names of sampling.placement + sampling.binning: uniform = grid + point (the paper), spread = "
        "grid + footprint, adaptive = adaptive + footprint";
    scheme.get = [](const SceneDesc& s) {
        const auto named = scheme_of(s.sampling);
        return json(named ? scheme_name(*named) : "adaptive placement with point binning");
    };
    scheme.put = [](SceneDesc& s, const json& v) {
        for (const NamedSampling& n : kSamplingSchemes)
            if (v.get<std::string>() == n.name) set_scheme(s.sampling, n.scheme);
    };
    t.push_back(scheme);
    t.push_back(number("sampling.tolerance_db", "dB", 0, 10, true, false, Stage::Trace,
                       "adaptive: target median |dB error| over echoing bins, as the sampler estimates it; "
                       "it refines until met",
                       [](S s) -> double& { return s.sampling.tolerance_db; }));
    t.push_back(number("sampling.tolerance_rel_l1", "", 0, 1, true, false, Stage::Trace,
                       "adaptive: target relative L1 error of the linear image (0.01: 1 %), as the sampler "
                       "estimates it; it refines until both this and tolerance_db are met",
                       [](S s) -> double& { return s.sampling.tolerance_rel_l1; }));
    t.push_back(integer("sampling.max_rays", 1000, kMaxRaysPerImage, Stage::Trace,
                        "adaptive: budget of rays per image, refinement and passes included; when reached, "
                        "refinement stops and the metadata says so (about 300 bytes of memory per ray)",
                        [](S s) -> int& { return s.sampling.max_rays; }));
    t.push_back(integer("sampling.bounces", 0, 2, Stage::Trace,
                        "Multipath: specular reflections followed per leg on mirrors (the water surface, "
                        "materials with reflection_db); 0: direct paths only",
                        [](S s) -> int& { return s.sampling.bounces; }));
    t.push_back(number("display.lo_db", "dB", -1000, 1000, false, false, Stage::Display,
                       "L_EN shown as black", [](S s) -> double& { return s.display.lo_db; }));
    t.push_back(number("display.hi_db", "dB", -1000, 1000, false, false, Stage::Display,
                       "L_EN shown as white", [](S s) -> double& { return s.display.hi_db; }));
    t.push_back(enumeration<Colormap>("display.colormap", {"gray", "viridis", "copper", "hot"},
                                      Stage::Display, "Colour map of the image (copper: ARIS-like)",
                                      [](S s) -> Colormap& { return s.display.colormap; }));
    t.push_back(
        sensor(boolean("display.auto", Stage::Display,
                       "Display range from the image itself: white at its 99.5th percentile (finite "
                       "levels), black at its 5th but at most 50 dB below white; instead of lo_db, hi_db",
                       [](S s) -> bool& { return s.display.auto_range; }),
               nullptr, true));
    add_sensor_params(t);
    t.push_back(boolean("export.auto", Stage::None,
                        "8-bit exports (.aris, MCAP uint8): byte 255 at the 99.5th percentile of the "
                        "exported frames' finite levels, byte 0 80 dB below (ARIS's 80 dB over 255 steps), "
                        "one mapping for all frames; instead of export.lo_db, export.hi_db",
                        [](S s) -> bool& { return s.exports.auto_range; }));
    t.push_back(number("export.lo_db", "dB", -1000, 1000, false, false, Stage::None,
                       "8-bit exports without export.auto: the image level written as byte 0 (and below)",
                       [](S s) -> double& { return s.exports.lo_db; }));
    t.push_back(number("export.hi_db", "dB", -1000, 1000, false, false, Stage::None,
                       "8-bit exports without export.auto: the image level written as byte 255 (and above)",
                       [](S s) -> double& { return s.exports.hi_db; }));
    t.push_back(number("export.start_time_s", "s", 0, 4102444800, false, false, Stage::None,
                       "UNIX time of the dataset's t = 0 in exports (ARIS FrameTime = start + t); 0: the "
                       "time batch prepared the dataset (or this value then), kept in DIR/dataset.json",
                       [](S s) -> double& { return s.exports.start_time_s; }));
    return t;
}

/// Keys scene files and `--set` accept that scene_to_json does not write: it writes sampling.scheme, the
/// name of their combination, so that every existing scene's metadata stays as it was.
std::vector<ParamSpec> build_input_params() {
    using S = SceneDesc&;
    return {
        enumeration<RayPlacement>(
            "sampling.placement", {"grid", "adaptive"}, Stage::Trace,
            "Where rays go: grid: elevation_rays x azimuth_rays per beam; adaptive: that "
            "grid refined until sampling.tolerance_db is met (needs footprint binning)",
            [](S s) -> RayPlacement& { return s.sampling.placement; }),
        enumeration<EchoBinning>(
            "sampling.binning", {"point", "footprint"}, Stage::Trace,
            "Where a ray's echo goes: point: the bin of its range (the paper); footprint: "
            "spread over the range interval its solid-angle cell covers",
            [](S s) -> EchoBinning& { return s.sampling.binning; }),
    };
}

MaterialSpec optional_material(MaterialSpec m) {
    m.optional = true;
    return m;
}

std::vector<MaterialSpec> build_material_params() {
    return {
        material("nu_db", "dB", -200, 50, false, "Lambert strength 10 log10 nu", &Material::nu_db),
        material("q", "", 0, 1000, false, "Lambert exponent q (fall-off at grazing)", &Material::q),
        material("mu", "", 0, 1e6, false, "Specular amplitude mu (linear; 0 = off)", &Material::mu),
        material("h_deg", "deg", 0, 90, true, "Specular lobe width h", &Material::h_deg),
        optional_material(material("reflection_db", "dB", 0, 200, false,
                                   "Multipath: energy lost per specular reflection, -10 log10 R^2; absent "
                                   "(null): not a mirror",
                                   &Material::reflection_db)),
        material("texture_rms_db", "dB", 0, 20, false,
                 "Seabed texture: rms of a random backscatter level fixed to the surface (linear mean kept); "
                 "0 = off",
                 &Material::texture_rms_db),
        material("texture_correlation_m", "m", 0, 1e4, true,
                 "Seabed texture and slope: lag at which their autocorrelation falls to 1/e",
                 &Material::texture_correlation_m),
        material("ripple_amplitude_db", "dB", 0, 20, false,
                 "Ripples: peak amplitude of a sinusoidal backscatter level (linear mean kept); 0 = off",
                 &Material::ripple_amplitude_db),
        material("ripple_wavelength_m", "m", 0, 1e4, true, "Ripples: crest spacing",
                 &Material::ripple_wavelength_m),
        material(
            "ripple_direction_deg", "deg", -360, 360, false,
            "Ripples: direction of the wave vector, from the surface's x axis toward y (seafloor: world)",
            &Material::ripple_direction_deg),
        material("slope_rms_deg", "deg", 0, 45, false,
                 "Small-scale slope: rms tilt of the facets in the plane of incidence; 0 = off",
                 &Material::slope_rms_deg),
    };
}

template <class Part>
PartSpec<Part> part(std::string key, std::string unit, ParamType type, double lo, double hi, bool lo_ex,
                    Stage stage, std::string help) {
    PartSpec<Part> p;
    p.key = std::move(key), p.unit = std::move(unit), p.type = type, p.help = std::move(help);
    p.min = lo, p.max = hi, p.min_exclusive = lo_ex, p.stage = stage;
    return p;
}

/// An object's vec3 member.
ObjectSpec object_vec3(std::string key, std::string unit, double lo, double hi, bool lo_ex, std::string help,
                       Vec3d ObjectDesc::*field) {
    ObjectSpec p = part<ObjectDesc>(std::move(key), std::move(unit), ParamType::Vec3, lo, hi, lo_ex,
                                    Stage::Geometry, std::move(help));
    p.get = [field](const ObjectDesc& o) { return json(o.*field); };
    p.put = [field](ObjectDesc& o, const json& v, const std::string&) { o.*field = v.get<Vec3d>(); };
    return p;
}

std::vector<ObjectSpec> build_object_params() {
    std::vector<ObjectSpec> t;
    ObjectSpec mesh =
        part<ObjectDesc>("mesh", "", ParamType::String, 0, 0, false, Stage::Geometry,
                         "Mesh file (" + mesh_extensions_text() + "), relative to the scene file");
    mesh.get = [](const ObjectDesc& o) {
        return o.box_m ? json(nullptr) : json(o.mesh_resolved.empty() ? o.mesh : o.mesh_resolved);
    };
    mesh.put = [](ObjectDesc& o, const json& v, const std::string& base) {
        o.mesh = v.get<std::string>();
        const std::filesystem::path p(o.mesh);
        o.mesh_resolved =
            p.is_absolute() ? p.string() : (std::filesystem::path(base) / p).lexically_normal().string();
        o.box_m.reset();
    };
    mesh.check = [](const ValueSpec&, const json& v, const std::string& file, const std::string& key) {
        if (!v.is_string() || v.get<std::string>().empty())
            throw InputError(file, key, "expected a non-empty path string (" + mesh_extensions_text() + ")");
        return v;
    };
    t.push_back(mesh);
    ObjectSpec box = part<ObjectDesc>("box", "m", ParamType::Vec3, 0, 1e4, true, Stage::Geometry,
                                      "Box size dx, dy, dz (instead of a mesh)");
    box.get = [](const ObjectDesc& o) { return o.box_m ? json(*o.box_m) : json(nullptr); };
    box.put = [](ObjectDesc& o, const json& v, const std::string&) {
        o.box_m = v.get<Vec3d>();
        o.mesh.clear(), o.mesh_resolved.clear();
    };
    t.push_back(box);
    t.push_back(object_vec3("position", "m", -1e6, 1e6, false, "Box centre / mesh origin x, y, z",
                            &ObjectDesc::position_m));
    t.push_back(object_vec3("orientation_deg", "deg", -360, 360, false, "Roll, pitch, yaw of the object",
                            &ObjectDesc::orientation_deg));
    ObjectSpec scale = object_vec3("scale", "", 0, 1e6, true, "Scale per axis, or one number for all three",
                                   &ObjectDesc::scale);
    scale.check = [](const ValueSpec& spec, const json& v, const std::string& file, const std::string& key) {
        if (!v.is_number()) return validate_value(spec, v, file, key);
        ValueSpec one = spec;
        one.type = ParamType::Number;
        const double x = validate_value(one, v, file, key).get<double>();
        return json(Vec3d{x, x, x});
    };
    t.push_back(scale);
    ObjectSpec crease = part<ObjectDesc>(
        "crease_angle_deg", "deg", ParamType::Number, 0, 180, false, Stage::Geometry,
        "Smooth shading: the normal at a hit is interpolated from corner normals that average "
        "the faces meeting there within this angle of each other; faces at a larger angle keep "
        "their edge (a box's 90 deg). 0: face normals");
    crease.get = [](const ObjectDesc& o) { return json(o.crease_angle_deg); };
    crease.put = [](ObjectDesc& o, const json& v, const std::string&) {
        o.crease_angle_deg = v.get<double>();
    };
    t.push_back(crease);
    ObjectSpec name = part<ObjectDesc>("name", "", ParamType::String, 0, 0, false, Stage::None, "A label");
    name.get = [](const ObjectDesc& o) { return json(o.name); };
    name.put = [](ObjectDesc& o, const json& v, const std::string&) { o.name = v.get<std::string>(); };
    name.check = [](const ValueSpec&, const json& v, const std::string& file, const std::string& key) {
        if (!v.is_string()) throw InputError(file, key, "expected a string");
        return v;
    };
    name.written = false;
    t.push_back(name);
    return t;
}

std::vector<SeafloorSpec> build_seafloor_params() {
    SeafloorSpec h = part<Seafloor>("height_m", "m", ParamType::Number, -1e6, 1e6, false, Stage::Trace,
                                    "Height z of the flat seafloor");
    h.get = [](const Seafloor& f) { return json(f.height_m); };
    h.put = [](Seafloor& f, const json& v, const std::string&) { f.height_m = v.get<double>(); };
    return {h};
}

std::string type_name(const json& v) {
    if (v.is_null()) return "null";
    if (v.is_boolean()) return "a boolean";
    if (v.is_number()) return "a number";
    if (v.is_string()) return "a string";
    if (v.is_array()) return "an array";
    return "an object";
}

void check_number(const ValueSpec& spec, double x, const std::string& file, const std::string& key) {
    const bool below = spec.min_exclusive ? !(x > spec.min) : !(x >= spec.min);
    const bool above = spec.max_exclusive ? !(x < spec.max) : !(x <= spec.max);
    if (!std::isfinite(x) || below || above)
        throw InputError(file, key, "value " + fmt(x) + " is out of range; allowed: " + allowed_text(spec));
}

} // namespace

const std::vector<ParamSpec>& scene_params() {
    static const std::vector<ParamSpec> table = build_scene_params();
    return table;
}

const std::vector<MaterialSpec>& material_params() {
    static const std::vector<MaterialSpec> table = build_material_params();
    return table;
}

const std::vector<ObjectSpec>& object_params() {
    static const std::vector<ObjectSpec> table = build_object_params();
    return table;
}

const std::vector<SeafloorSpec>& seafloor_params() {
    static const std::vector<SeafloorSpec> table = build_seafloor_params();
    return table;
}

const ObjectSpec* find_object_param(const std::string& key) {
    for (auto& p : object_params())
        if (p.key == key) return &p;
    return nullptr;
}

const SeafloorSpec* find_seafloor_param(const std::string& key) {
    for (auto& p : seafloor_params())
        if (p.key == key) return &p;
    return nullptr;
}

const std::vector<ParamSpec>& input_params() {
    static const std::vector<ParamSpec> table = build_input_params();
    return table;
}

const ParamSpec* find_param(const std::string& key) {
    for (auto& p : scene_params())
        if (p.key == key) return &p;
    for (auto& p : input_params())
        if (p.key == key) return &p;
    return nullptr;
}

const MaterialSpec* find_material_param(const std::string& key) {
    for (auto& p : material_params())
        if (p.key == key) return &p;
    return nullptr;
}

std::string allowed_text(const ValueSpec& spec) {
    if (spec.type == ParamType::Enum) {
        std::string s = "one of";
        for (size_t i = 0; i < spec.choices.size(); ++i) s += (i ? ", \"" : " \"") + spec.choices[i] + "\"";
        return s;
    }
    std::string range = std::string(spec.min_exclusive ? "(" : "[") + fmt(spec.min) + ", " + fmt(spec.max) +
                        (spec.max_exclusive ? ")" : "]");
    std::string unit = spec.unit.empty() ? "" : " " + spec.unit;
    if (spec.type == ParamType::Bool) return "true or false";
    if (spec.type == ParamType::String) return "a string";
    if (spec.type == ParamType::Integer) return "an integer in " + range;
    if (spec.type == ParamType::Vec3) return "an array of 3 finite numbers in " + range + unit;
    return "a finite number in " + range + unit + (spec.optional ? ", or null (absent)" : "");
}

double MaterialSpec::value_of(const json& v) const {
    return v.is_null() ? std::numeric_limits<double>::infinity() : v.get<double>();
}

json MaterialSpec::get(const Material& m) const {
    const double v = m.*field;
    return std::isfinite(v) ? json(v) : json(nullptr);
}

Stage ValueSpec::effective_stage(const SceneDesc& scene) const {
    return steers_sampler && scene.sampling.placement == RayPlacement::Adaptive
               ? std::min(stage, Stage::Trace)
               : stage;
}

Stage MaterialSpec::stage_of_change(double before, double after, const SceneDesc& scene) const {
    return optional && std::isfinite(before) != std::isfinite(after) ? Stage::Trace : effective_stage(scene);
}

json validate_value(const ValueSpec& spec, const json& v, const std::string& file, const std::string& key) {
    if (spec.optional && v.is_null()) return v;
    switch (spec.type) {
    case ParamType::Number:
        if (!v.is_number())
            throw InputError(file, key, "expected " + allowed_text(spec) + ", got " + type_name(v));
        check_number(spec, v.get<double>(), file, key);
        return json(v.get<double>());
    case ParamType::Integer: {
        if (!v.is_number())
            throw InputError(file, key, "expected " + allowed_text(spec) + ", got " + type_name(v));
        const double x = v.get<double>();
        if (!std::isfinite(x) || x != std::floor(x))
            throw InputError(file, key,
                             "value " + fmt(x) + " is not an integer; allowed: " + allowed_text(spec));
        check_number(spec, x, file, key);
        return json(int(x));
    }
    case ParamType::Vec3: {
        if (!v.is_array() || v.size() != 3)
            throw InputError(file, key,
                             "expected " + allowed_text(spec) + ", got " +
                                 (v.is_array() ? "an array of " + std::to_string(v.size()) : type_name(v)));
        Vec3d out{};
        for (size_t i = 0; i < 3; ++i) {
            const std::string ki = key + "[" + std::to_string(i) + "]";
            if (!v[i].is_number()) throw InputError(file, ki, "expected a number, got " + type_name(v[i]));
            check_number(spec, v[i].get<double>(), file, ki);
            out[i] = v[i].get<double>();
        }
        return json(out);
    }
    case ParamType::String:
        if (!v.is_string()) throw InputError(file, key, "expected a string, got " + type_name(v));
        return v;
    case ParamType::Bool:
        if (!v.is_boolean()) throw InputError(file, key, "expected true or false, got " + type_name(v));
        return v;
    case ParamType::Enum:
        if (v.is_string())
            for (auto& c : spec.choices)
                if (c == v.get<std::string>()) return v;
        throw InputError(file, key,
                         "got " + (v.is_string() ? "\"" + v.get<std::string>() + "\"" : type_name(v)) +
                             "; allowed: " + allowed_text(spec));
    }
    return v;
}

bool is_group_key(const std::string& key) {
    return key == "sonar.device" || key == "sensor.model";
}

namespace {

/// sensor.model: each row with a value for the model takes it: for "device" the preset's where it gives
/// one, else the row's generic device value (null: left as it is).
void apply_sensor_model(SceneDesc& scene) {
    const DevicePreset* preset = find_device(scene.sonar.device);
    const bool device = scene.sensor.model == SensorModel::Device;
    for (auto& p : scene_params()) {
        if (p.ideal_value.is_null() && p.device_value.is_null()) continue;
        json v = device ? p.device_value : p.ideal_value;
        if (device && preset)
            for (auto& dv : preset->values)
                if (dv.key == p.key) v = dv.value;
        if (!v.is_null()) p.put(scene, validate_value(p, v, preset ? preset->file : "sensor.model", p.key));
    }
}

/// sonar.device: the preset's values; its effect switches (rows with an "ideal" value) only under
/// sensor.model "device".
void apply_device(SceneDesc& scene) {
    const DevicePreset* preset = find_device(scene.sonar.device);
    if (!preset) return; // "none": the values stay as they are
    for (auto& dv : preset->values) {
        const ParamSpec* p = find_param(dv.key);
        if (!p || is_group_key(dv.key) || p->type == ParamType::Vec3 || dv.key == "sensor.seed" ||
            dv.key.rfind("sampling.", 0) == 0)
            throw InputError(preset->file, "values." + dv.key, "not a parameter a device preset may set");
        if (p->ideal_value.is_null()) p->put(scene, validate_value(*p, dv.value, preset->file, dv.key));
    }
    if (scene.sensor.model == SensorModel::Device) apply_sensor_model(scene);
}

} // namespace

std::string material_keys_text() {
    std::string keys;
    for (auto& p : material_params()) keys += (keys.empty() ? "" : ", ") + p.key;
    return keys;
}

void set_material(Material& m, const std::string& field, const json& value, const std::string& file,
                  const std::string& key) {
    const MaterialSpec* spec = find_material_param(field);
    if (!spec) throw InputError(file, key, "unknown key; allowed: " + material_keys_text());
    m.*(spec->field) = spec->value_of(validate_value(*spec, value, file, key));
}

namespace {

void set_value(SceneDesc& scene, const std::string& key, const json& value, const std::string& file) {
    if (auto* p = find_param(key)) {
        p->put(scene, validate_value(*p, value, file, key));
        if (key == "sonar.device") apply_device(scene);
        if (key == "sensor.model") apply_sensor_model(scene);
        return;
    }
    const std::string surface_prefix = "water.surface_material.";
    if (key.rfind(surface_prefix, 0) == 0) {
        set_material(scene.water.surface_material, key.substr(surface_prefix.size()), value, file, key);
        return;
    }
    if (key.rfind("seafloor.material.", 0) == 0) {
        if (!scene.seafloor) throw InputError(file, key, "the scene has no seafloor");
        set_material(scene.seafloor->material, key.substr(18), value, file, key);
        return;
    }
    if (key.rfind("seafloor.", 0) == 0)
        if (const SeafloorSpec* p = find_seafloor_param(key.substr(9))) {
            const json v = p->validated(value, file, key);
            if (!scene.seafloor) scene.seafloor = Seafloor{};
            p->put(*scene.seafloor, v, "");
            return;
        }
    if (key.rfind("objects.", 0) == 0) {
        const std::string rest = key.substr(8);
        const size_t dot = rest.find('.');
        size_t idx = 0;
        const std::string idx_text = rest.substr(0, dot);
        if (idx_text.empty() || idx_text.find_first_not_of("0123456789") != std::string::npos ||
            idx_text.size() > 6 || (idx = std::stoul(idx_text)) >= scene.objects.size())
            throw InputError(file, key,
                             "object index must be in [0, " + std::to_string(scene.objects.size()) + ")");
        const std::string field = dot == std::string::npos ? "" : rest.substr(dot + 1);
        ObjectDesc& o = scene.objects[idx];
        if (field.rfind("material.", 0) == 0) {
            set_material(o.material, field.substr(9), value, file, key);
            return;
        }
        const ObjectSpec* p = find_object_param(field);
        if (!p)
            throw InputError(file, key, "unknown key; allowed: " + part_keys_text(object_params()) + ".*");
        // A mesh path given on the command line or in the viewer is relative to the working directory.
        std::error_code ec;
        p->put(o, p->validated(value, file, key), std::filesystem::current_path(ec).string());
        return;
    }
    std::string known;
    for (const auto* list : {&scene_params(), &input_params()})
        for (auto& p : *list) known += (known.empty() ? "" : ", ") + p.key;
    for (auto& p : seafloor_params()) known += ", seafloor." + p.key;
    throw InputError(file, key,
                     "unknown key; allowed: " + known +
                         ", seafloor.material.*, water.surface_material.*, objects.N.*");
}

} // namespace

Stage apply_setting(SceneDesc& scene, const std::string& key, const json& value, const std::string& file) {
    const SceneDesc before = scene;
    set_value(scene, key, value, file);
    return changed_stage(before, scene);
}

Stage changed_stage(const SceneDesc& a, const SceneDesc& b) {
    Stage st = Stage::None;
    auto mark = [&](Stage s) { st = std::min(st, s); };
    for (auto& p : scene_params())
        if (p.get(a) != p.get(b)) mark(p.effective_stage(b));
    auto material_stage = [&](const Material& x, const Material& y) {
        for (auto& p : material_params())
            if (p.get(x) != p.get(y)) mark(p.stage_of_change(x.*p.field, y.*p.field, b));
    };
    material_stage(a.water.surface_material, b.water.surface_material);
    if (a.objects.size() != b.objects.size()) {
        mark(Stage::Geometry);
    } else {
        for (size_t i = 0; i < a.objects.size(); ++i) {
            for (auto& p : object_params())
                if (p.get(a.objects[i]) != p.get(b.objects[i])) mark(p.effective_stage(b));
            material_stage(a.objects[i].material, b.objects[i].material);
        }
    }
    if (bool(a.seafloor) != bool(b.seafloor))
        mark(Stage::Trace);
    else if (a.seafloor) {
        for (auto& p : seafloor_params())
            if (p.get(*a.seafloor) != p.get(*b.seafloor)) mark(p.effective_stage(b));
        material_stage(a.seafloor->material, b.seafloor->material);
    }
    return st;
}

std::pair<std::string, json> parse_setting_text(const std::string& text, const std::string& origin) {
    const size_t eq = text.find('=');
    if (eq == std::string::npos || eq == 0)
        throw InputError(origin, text, "expected key.path=value, e.g. sonar.range_max_m=8");
    const std::string key = text.substr(0, eq), raw = text.substr(eq + 1);
    json value = json::parse(raw, nullptr, false);
    if (value.is_discarded()) {
        // A bare word: enum names such as paper, viridis. Anything else that is not JSON is an error (a
        // number out of double range such as 1e400 must not turn into a string or an infinity).
        const bool word = !raw.empty() && std::isalpha(static_cast<unsigned char>(raw[0])) &&
                          raw.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                "0123456789_-") == std::string::npos;
        if (!word) {
            std::string allowed;
            if (const ParamSpec* p = find_param(key)) allowed = "; allowed: " + allowed_text(*p);
            throw InputError(origin, key,
                             raw.empty() ? "missing value after '='" + allowed
                                         : "cannot read value \"" + raw + "\"" + allowed);
        }
        value = json(raw);
    }
    return {key, value};
}

Stage apply_setting_text(SceneDesc& scene, const std::string& text, const std::string& origin) {
    const auto [key, value] = parse_setting_text(text, origin);
    return apply_setting(scene, key, value, origin);
}

void validate_scene(const SceneDesc& s, const std::string& file, const std::vector<std::string>& just_set) {
    // Whether `b`, not `a`, is the key to name: the caller has just set b and not a.
    auto second = [&](const char* a, const char* b) {
        auto set = [&](const char* k) {
            return std::find(just_set.begin(), just_set.end(), k) != just_set.end();
        };
        return set(b) && !set(a);
    };
    // "KEY (value) must be below OTHER (value)", said of the key the caller set.
    auto order = [&](const char* lo_key, double lo, const char* hi_key, double hi) {
        auto name = [](const char* k) { return std::string(std::strrchr(k, '.') + 1); };
        if (second(lo_key, hi_key))
            throw InputError(file, hi_key,
                             name(hi_key) + " (" + fmt(hi) + ") must be above " + name(lo_key) + " (" +
                                 fmt(lo) + ")");
        throw InputError(file, lo_key,
                         name(lo_key) + " (" + fmt(lo) + ") must be below " + name(hi_key) + " (" + fmt(hi) +
                             ")");
    };
    if (!(s.sonar.range_min_m < s.sonar.range_max_m))
        order("sonar.range_min_m", s.sonar.range_min_m, "sonar.range_max_m", s.sonar.range_max_m);
    if (s.sampling.placement == RayPlacement::Adaptive && s.sampling.binning == EchoBinning::Point)
        throw InputError(file, "sampling.binning",
                         "adaptive placement needs \"footprint\" binning (its refinement and error estimate "
                         "assume each cell's echo spread over its range footprint): use sampling.placement "
                         "\"grid\" with \"point\" binning (sampling.scheme \"uniform\")");
    if (s.sampling.normals == NormalSource::Paper && s.sampling.placement == RayPlacement::Adaptive)
        throw InputError(file, "sampling.normals",
                         "\"paper\" normals need the regular ray grid: use sampling.scheme \"uniform\" or "
                         "\"spread\" with them");
    const double rays = double(s.sonar.beams) * s.sampling.azimuth_rays * s.sampling.elevation_rays;
    if (rays > kMaxRaysPerImage)
        throw InputError(file, "sampling.elevation_rays",
                         "beams x azimuth_rays x elevation_rays = " + fmt(rays) + " exceeds the limit of " +
                             fmt(kMaxRaysPerImage) + " rays per image");
    // Ranges are carried in single precision; a bin narrower than 1 um resolves nothing.
    const double bin_m = (s.sonar.range_max_m - s.sonar.range_min_m) / s.sonar.range_bins;
    if (!(bin_m >= kMinRangeBinM))
        throw InputError(file, "sonar.range_bins",
                         "range bins of " + fmt(bin_m) +
                             " m ((range_max_m - range_min_m) / range_bins) are below " + "the minimum of " +
                             fmt(kMinRangeBinM) + " m; use fewer bins or a wider window");
    const double cells = double(s.sonar.range_bins) * s.sonar.beams;
    if (cells > kMaxImageCells)
        throw InputError(file, "sonar.range_bins",
                         "range_bins x beams = " + fmt(cells) + " exceeds the limit of " +
                             fmt(kMaxImageCells) + " cells per image");
    const double sector_px = sector_image_pixels(s.sonar);
    if (!(sector_px <= kMaxImageCells))
        throw InputError(
            file,
            second("sonar.range_min_m", "sonar.range_max_m") ? "sonar.range_max_m" : "sonar.range_min_m",
            "the sector image would have " + fmt(sector_px) + " pixels (limit " + fmt(kMaxImageCells) +
                "): range_min_m is too close to range_max_m for this field of view");
    const ElevationWeight elevation(s);
    if (!(rad2deg(elevation.traced_fov_rad()) < 180))
        throw InputError(
            file, "sensor.elevation_beamwidth_deg",
            "the elevation pattern would be traced over " + fmt(rad2deg(elevation.traced_fov_rad())) +
                " deg; it must stay below 180 deg (gaussian: 3.16 x, sinc: 4.5 x the -3 dB width)");
    if (s.sensor.range_resolution_m > (s.sonar.range_max_m - s.sonar.range_min_m) / 4)
        throw InputError(file, "sensor.range_resolution_m",
                         "value " + fmt(s.sensor.range_resolution_m) +
                             " m is coarser than a quarter of the range window; allowed: [0, " +
                             fmt((s.sonar.range_max_m - s.sonar.range_min_m) / 4) + "] m");
    if (const auto& h = s.water.surface_height_m) {
        if (!(s.sonar.pose.position_m[2] < *h))
            throw InputError(file, "water.surface_height_m",
                             "the sonar (z = " + fmt(s.sonar.pose.position_m[2]) +
                                 " m) must be below the water surface (z = " + fmt(*h) + " m)");
        if (s.seafloor && !(s.seafloor->height_m < *h))
            throw InputError(file, "water.surface_height_m",
                             "the seafloor (z = " + fmt(s.seafloor->height_m) +
                                 " m) must be below the water surface (z = " + fmt(*h) + " m)");
    }
    if (!(s.display.lo_db < s.display.hi_db))
        order("display.lo_db", s.display.lo_db, "display.hi_db", s.display.hi_db);
    if (!s.exports.auto_range && !(s.exports.lo_db < s.exports.hi_db))
        order("export.lo_db", s.exports.lo_db, "export.hi_db", s.exports.hi_db);
    for (size_t i = 0; i < s.objects.size(); ++i) {
        const auto& o = s.objects[i];
        for (double c : o.scale)
            if (!(c > 0) || !std::isfinite(c))
                throw InputError(file, "objects[" + std::to_string(i) + "].scale",
                                 "scale must be finite and > 0");
    }
}

double sector_image_pixels(const SonarParams& s) {
    // The fan's geometry as SectorLayout (image.cpp) lays it out at its default height, in double
    // precision so that absurd windows give a large number instead of an int overflow.
    const double height = std::clamp(s.range_bins, 256, 2048);
    const double half = s.azimuth_fov_deg / 2 * 3.14159265358979323846 / 180;
    const double m_per_px = (s.range_max_m - s.range_min_m * std::cos(half)) / height;
    const double width = std::max(16.0, std::ceil(2 * s.range_max_m * std::sin(half) / m_per_px));
    return width * height;
}

std::string params_markdown() {
    // A "|" inside a cell (e.g. "|dB error|") would end the cell: escape it.
    auto cell = [](const std::string& s) {
        std::string out;
        for (char c : s) out += c == '|' ? std::string("\\|") : std::string(1, c);
        return out;
    };
    SceneDesc defaults;
    std::ostringstream md;
    md << "| key | unit | default | allowed | what |\n|---|---|---|---|---|\n";
    for (const auto* list : {&scene_params(), &input_params()})
        for (auto& p : *list)
            md << "| `" << p.key << "` | " << p.unit << " | `" << p.get(defaults).dump() << "` | "
               << cell(allowed_text(p)) << " | " << cell(p.help) << " |\n";
    Material m;
    for (auto& p : material_params())
        md << "| `material." << p.key << "` | " << p.unit << " | `" << p.get(m).dump() << "` | "
           << cell(allowed_text(p)) << " | " << cell(p.help) << " |\n";
    return md.str();
}

} // namespace sonarsim

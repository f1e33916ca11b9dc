#include "params.hpp"

#include "errors.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
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
    m.help = std::move(help);
    m.field = field;
    return m;
}

std::vector<ParamSpec> build_scene_params() {
    using S = SceneDesc&;
    std::vector<ParamSpec> t;
    t.push_back(vec3("sonar.position", "m", -1e6, 1e6, Stage::Trace, "Sonar position x, y, z (world, z up)",
                     [](S s) -> Vec3d& { return s.sonar.pose.position_m; }));
    t.push_back(vec3("sonar.orientation_deg", "deg", -360, 360, Stage::Trace,
                     "Roll, pitch, yaw; R = Rz(yaw) Ry(pitch) Rx(roll); positive pitch looks down",
                     [](S s) -> Vec3d& { return s.sonar.pose.orientation_deg; }));
    t.push_back(number("sonar.frequency_khz", "kHz", 1, 10000, false, false, Stage::Shade,
                       "Carrier frequency f (absorption, eq. 7)",
                       [](S s) -> double& { return s.sonar.frequency_khz; }));
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
    t.push_back(number("water.temperature_c", "degC", -2, 35, false, false, Stage::Shade,
                       "Water temperature T (absorption formula range)",
                       [](S s) -> double& { return s.water.temperature_c; }));
    t.push_back(number("water.depth_m", "m", 0, 7000, false, false, Stage::Shade,
                       "Water depth D (absorption)", [](S s) -> double& { return s.water.depth_m; }));
    t.push_back(integer("sampling.elevation_rays", 1, 1000000, Stage::Trace, "Elevation rays M per beam",
                        [](S s) -> int& { return s.sampling.elevation_rays; }));
    t.push_back(integer("sampling.azimuth_rays", 1, 1024, Stage::Trace, "Azimuth rays per beam",
                        [](S s) -> int& { return s.sampling.azimuth_rays; }));
    t.push_back(enumeration<NormalSource>(
        "sampling.normals", {"mesh", "paper"}, Stage::Trace,
        "Incidence from the true surface normal, or the paper's neighbour-difference normal (eq. 13-14)",
        [](S s) -> NormalSource& { return s.sampling.normals; }));
    t.push_back(enumeration<SamplingScheme>(
        "sampling.scheme", {"uniform", "spread", "adaptive"}, Stage::Trace,
        "uniform: each ray's echo in the bin of its range (the paper); spread: each ray's echo spread over "
        "the range interval its solid-angle cell covers; adaptive: spread, with elevation cells refined "
        "until sampling.tolerance_db is met",
        [](S s) -> SamplingScheme& { return s.sampling.scheme; }));
    t.push_back(number("sampling.tolerance_db", "dB", 0, 10, true, false, Stage::Trace,
                       "adaptive: target median |dB error| over echoing bins, as the sampler estimates it; "
                       "it refines until met",
                       [](S s) -> double& { return s.sampling.tolerance_db; }));
    t.push_back(integer("sampling.max_rays", 1000, kMaxRaysPerImage, Stage::Trace,
                        "adaptive: budget of rays per image, refinement and passes included; when reached, "
                        "refinement stops and the metadata says so (about 300 bytes of memory per ray)",
                        [](S s) -> int& { return s.sampling.max_rays; }));
    t.push_back(number("display.lo_db", "dB", -1000, 1000, false, false, Stage::Display,
                       "L_EN shown as black", [](S s) -> double& { return s.display.lo_db; }));
    t.push_back(number("display.hi_db", "dB", -1000, 1000, false, false, Stage::Display,
                       "L_EN shown as white", [](S s) -> double& { return s.display.hi_db; }));
    t.push_back(enumeration<Colormap>("display.colormap", {"gray", "viridis"}, Stage::Display,
                                      "Colour map of the image",
                                      [](S s) -> Colormap& { return s.display.colormap; }));
    return t;
}

std::vector<MaterialSpec> build_material_params() {
    return {
        material("nu_db", "dB", -200, 50, false, "Lambert strength 10 log10 nu", &Material::nu_db),
        material("q", "", 0, 1000, false, "Lambert exponent q (fall-off at grazing)", &Material::q),
        material("mu", "", 0, 1e6, false, "Specular amplitude mu (linear; 0 = off)", &Material::mu),
        material("h_deg", "deg", 0, 90, true, "Specular lobe width h", &Material::h_deg),
    };
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

const ParamSpec* find_param(const std::string& key) {
    for (auto& p : scene_params())
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
    if (spec.type == ParamType::Integer) return "an integer in " + range;
    if (spec.type == ParamType::Vec3) return "an array of 3 finite numbers in " + range + unit;
    return "a finite number in " + range + unit;
}

json validate_value(const ValueSpec& spec, const json& v, const std::string& file, const std::string& key) {
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

Stage apply_setting(SceneDesc& scene, const std::string& key, const json& value, const std::string& file) {
    if (auto* p = find_param(key)) {
        p->put(scene, validate_value(*p, value, file, key));
        return p->stage;
    }
    const std::string floor_prefix = "seafloor.material.";
    if (key.rfind(floor_prefix, 0) == 0) {
        auto* m = find_material_param(key.substr(floor_prefix.size()));
        if (!m) throw InputError(file, key, "unknown material key; allowed: nu_db, q, mu, h_deg");
        if (!scene.seafloor) throw InputError(file, key, "the scene has no seafloor");
        scene.seafloor->material.*(m->field) = validate_value(*m, value, file, key).get<double>();
        return Stage::Shade;
    }
    if (key == "seafloor.height_m") {
        ValueSpec s;
        s.key = key, s.unit = "m", s.min = -1e6, s.max = 1e6;
        if (!scene.seafloor) scene.seafloor = Seafloor{};
        scene.seafloor->height_m = validate_value(s, value, file, key).get<double>();
        return Stage::Trace;
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
            auto* m = find_material_param(field.substr(9));
            if (!m) throw InputError(file, key, "unknown material key; allowed: nu_db, q, mu, h_deg");
            o.material.*(m->field) = validate_value(*m, value, file, key).get<double>();
            return Stage::Shade;
        }
        ValueSpec s;
        s.key = key, s.type = ParamType::Vec3, s.min = -1e6, s.max = 1e6;
        if (field == "position") {
            o.position_m = validate_value(s, value, file, key).get<Vec3d>();
        } else if (field == "orientation_deg") {
            s.min = -360, s.max = 360;
            o.orientation_deg = validate_value(s, value, file, key).get<Vec3d>();
        } else {
            throw InputError(file, key,
                             "unknown object key for --set; allowed: position, orientation_deg, material.*");
        }
        return Stage::Geometry;
    }
    std::string known;
    for (auto& p : scene_params()) known += (known.empty() ? "" : ", ") + p.key;
    throw InputError(file, key,
                     "unknown key; allowed: " + known +
                         ", seafloor.height_m, seafloor.material.*, objects.N.*");
}

Stage apply_setting_text(SceneDesc& scene, const std::string& text, const std::string& origin) {
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
    return apply_setting(scene, key, value, origin);
}

void validate_scene(const SceneDesc& s, const std::string& file) {
    if (!(s.sonar.range_min_m < s.sonar.range_max_m))
        throw InputError(file, "sonar.range_min_m",
                         "range_min_m (" + fmt(s.sonar.range_min_m) + ") must be below range_max_m (" +
                             fmt(s.sonar.range_max_m) + ")");
    if (s.sampling.normals == NormalSource::Paper && s.sampling.scheme == SamplingScheme::Adaptive)
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
        throw InputError(file, "sonar.range_min_m",
                         "the sector image would have " + fmt(sector_px) + " pixels (limit " +
                             fmt(kMaxImageCells) +
                             "): range_min_m is too close to range_max_m for this field of view");
    if (!(s.display.lo_db < s.display.hi_db))
        throw InputError(file, "display.lo_db", "lo_db must be below hi_db");
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
    SceneDesc defaults;
    std::ostringstream md;
    md << "| key | unit | default | allowed | what |\n|---|---|---|---|---|\n";
    for (auto& p : scene_params())
        md << "| `" << p.key << "` | " << p.unit << " | `" << p.get(defaults).dump() << "` | "
           << allowed_text(p) << " | " << p.help << " |\n";
    Material m;
    for (auto& p : material_params())
        md << "| `material." << p.key << "` | " << p.unit << " | `" << m.*(p.field) << "` | "
           << allowed_text(p) << " | " << p.help << " |\n";
    return md.str();
}

} // namespace sonarsim

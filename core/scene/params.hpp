// The one table of parameters: name, unit, default, bounds and help for every scene key.
// It drives the scene-file parser, `--set`, validation, the viewer's sliders and the docs.
#pragma once
#include "core/scene/scene.hpp"

#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

namespace sonarsim {

using json = nlohmann::json;

enum class ParamType { Number, Integer, Vec3, Enum, Bool, String };

/// What must be recomputed when a parameter changes (each stage implies the ones after it).
enum class Stage { Geometry = 0, Trace = 1, Shade = 2, Sensor = 3, Display = 4, None = 5 };

/// Bounds and documentation of one value. Numbers: min/max bounds (exclusive where flagged).
struct ValueSpec {
    std::string key;  ///< dotted key, relative to its table ("sonar.range_max_m" or "nu_db")
    std::string unit; ///< "m", "deg", "dB", "" ...
    ParamType type = ParamType::Number;
    double min = 0, max = 0;
    bool min_exclusive = false, max_exclusive = false;
    std::vector<std::string> choices; ///< for Enum
    std::string help;
    Stage stage = Stage::Trace;
    bool optional = false; ///< null (or absent from a scene file) is allowed: the value is absent
    /// The adaptive sampler places its rays by this value (it shapes how the echo varies over a surface or
    /// between materials): under the adaptive scheme a change re-traces, otherwise it costs `stage`.
    bool steers_sampler = false;
    /// What a change of this value recomputes in `scene` (the scene after the change).
    Stage effective_stage(const SceneDesc& scene) const;
};

/// A scene-level parameter with accessors into SceneDesc.
struct ParamSpec : ValueSpec {
    std::function<json(const SceneDesc&)> get;
    std::function<void(SceneDesc&, const json&)> put; ///< value already validated
    /// Sensor rows: the value sensor.model "ideal" sets (null: the model leaves it alone) and the one
    /// "device" sets when the device preset does not give one (null: leaves it alone).
    json ideal_value, device_value;
};

/// Keys that choose a group of other values: sonar.device (a preset's values) and sensor.model (the sensor's
/// effects). A scene applies them before all its other keys, so that explicit keys override what they chose.
bool is_group_key(const std::string& key);

/// A per-material parameter with accessors into Material. An optional one (reflection_db) is absent as
/// +infinity.
struct MaterialSpec : ValueSpec {
    double Material::*field = nullptr;
    /// The field's value from a validated JSON value (null: absent).
    double value_of(const json& validated) const;
    /// The field as JSON (null when absent).
    json get(const Material& m) const;
    /// What changing the field from `before` to `after` in `scene` (after the change) invalidates: a mirror
    /// appearing or disappearing changes the traced paths, any other change the row's effective stage.
    Stage stage_of_change(double before, double after, const SceneDesc& scene) const;
};

const std::vector<ParamSpec>& scene_params();
/// Keys read (scene files, `--set`, find_param) but not written by scene_to_json: sampling.placement and
/// sampling.binning, written as sampling.scheme (the name of their combination).
const std::vector<ParamSpec>& input_params();
const std::vector<MaterialSpec>& material_params();
const ParamSpec* find_param(const std::string& key);
const MaterialSpec* find_material_param(const std::string& key);

/// Sets material field `field` ("nu_db", "reflection_db", ...) from `value`. `key` names the whole key
/// path in errors.
void set_material(Material& m, const std::string& field, const json& value, const std::string& file,
                  const std::string& key);

/// "nu_db, q, mu, h_deg, reflection_db": the material keys, for error messages.
std::string material_keys_text();

/// Check `value` against `spec`; throws InputError(file, key_path, "... allowed ...") when it does not fit.
/// Returns the value in canonical form (integers as integers, vec3 as 3 numbers).
json validate_value(const ValueSpec& spec, const json& value, const std::string& file,
                    const std::string& key_path);

/// A key of one part of a scene (an object, the seafloor) with accessors into it. Its material's keys are
/// the material rows ("objects.N.material.q").
template <class Part> struct PartSpec : ValueSpec {
    std::function<json(const Part&)> get; ///< null: absent (mesh of a box), not written
    /// Sets the value (already validated); `base_dir` resolves relative mesh paths.
    std::function<void(Part&, const json&, const std::string& base_dir)> put;
    /// Validation beyond validate_value (a mesh path, a name, a scale given as one number); null: none.
    std::function<json(const ValueSpec&, const json&, const std::string& file, const std::string& key)> check;
    bool written = true; ///< scene_to_json writes it (a name is a label only)
    /// The value checked against the row: `check`, else validate_value.
    json validated(const json& value, const std::string& file, const std::string& key) const {
        return check ? check(*this, value, file, key) : validate_value(*this, value, file, key);
    }
};
using ObjectSpec = PartSpec<ObjectDesc>;
using SeafloorSpec = PartSpec<Seafloor>;

/// Object keys (mesh, box, position, orientation_deg, scale, crease_angle_deg, name): stage Geometry (name:
/// None).
const std::vector<ObjectSpec>& object_params();
/// Seafloor keys (height_m).
const std::vector<SeafloorSpec>& seafloor_params();
const ObjectSpec* find_object_param(const std::string& key);
const SeafloorSpec* find_seafloor_param(const std::string& key);
/// "KEYS, material": the keys of a part, for error messages ("mesh, box, ..., material").
template <class Part> std::string part_keys_text(const std::vector<PartSpec<Part>>& rows) {
    std::string keys;
    for (auto& p : rows) keys += p.key + ", ";
    return keys + "material";
}

/// Human-readable description of what is allowed, e.g. "a number in (0, 180)".
std::string allowed_text(const ValueSpec& spec);

/// Apply `key_path = value` to the scene: scene params, "seafloor.material.nu_db",
/// "objects.N.position", "objects.N.material.q", ... Returns the stage it invalidates: changed_stage of the
/// scene before and after.
Stage apply_setting(SceneDesc& scene, const std::string& key_path, const json& value,
                    const std::string& file);

/// Parse "key.path=value" (value as JSON, or a bare word for enums) into key and value.
std::pair<std::string, json> parse_setting_text(const std::string& assignment, const std::string& origin);

/// Parse "key.path=value" (value as JSON, or a bare word for enums) and apply it.
Stage apply_setting_text(SceneDesc& scene, const std::string& assignment, const std::string& origin);

/// Earliest stage at which two scenes differ (Stage::None if they render identically), from the table
/// alone: the earliest effective stage of the rows whose values differ.
Stage changed_stage(const SceneDesc& before, const SceneDesc& after);

/// Cross-field checks (range_min < range_max, ray buffers that fit in memory, ...). A check between two
/// keys names the one of them in `just_set` (the keys the caller has just set, e.g. by `--set`), the first
/// otherwise.
void validate_scene(const SceneDesc& scene, const std::string& file,
                    const std::vector<std::string>& just_set = {});

/// Upper bound on the rays of one image; larger requests are rejected, not clamped.
constexpr double kMaxRaysPerImage = 5.0e7;

/// Upper bound on range_bins x beams and on the sector image's pixels (2^26: 256 MiB of float32).
constexpr double kMaxImageCells = 67108864.0;

/// Narrowest range bin [m]: ranges are carried in single precision.
constexpr double kMinRangeBinM = 1e-6;

/// Pixels of the sector (fan) image at its default height; validate_scene bounds it by kMaxImageCells.
double sector_image_pixels(const SonarParams& sonar);

/// Markdown table of all parameters (for docs and `sonarsim params`).
std::string params_markdown();

} // namespace sonarsim

// The one table of parameters: every scene key's row (param_spec.hpp), looked up by key, applied by
// `--set` and the viewer, checked, compared (what an edit invalidates) and documented. Where each part lives:
// the rows in scene/rows/*.cpp (assembled in params.cpp), value and cross-field checks in value_check.cpp and
// validate_scene.cpp, group keys (device presets, the sensor model) in presets.cpp, key routing and `--set`
// in settings.cpp, stages in stages.cpp, Markdown in params_markdown.cpp.
#pragma once
#include "core/scene/param_spec.hpp"
#include "core/data/scene.hpp"

#include <string>
#include <utility>
#include <vector>

namespace sonarsim {

/// Keys that choose a group of other values: sonar.device (a preset's values), sonar.kind (the rows of other
/// kinds back to their defaults) and sensor.model (the sensor's effects), in the order a scene applies them:
/// before all its other keys, so that explicit keys override what they chose.
const std::vector<std::string>& group_keys();
bool is_group_key(const std::string& key);

/// After `key` (a group key) was set in `scene`: the values it chooses (a preset's, the sensor model's).
void apply_group_key(SceneDesc& scene, const std::string& key);

/// Sets every row the scene's kind (sonar.kind) does not use to its default: a device preset of a kind does
/// so, and the viewer's kind selector.
void reset_other_kinds_rows(SceneDesc& scene);
/// "imaging", "sidescan", "scanning": the kind's name in sonar.kind.
std::string kind_name(SonarKind kind);

/// "sonar.frequency_khz, sonar.azimuth_fov_deg, ...": the keys a device preset may set (preset_may_set).
std::string preset_keys_text();

const std::vector<ParamSpec>& scene_params();
/// Keys read (scene files, `--set`, find_param) but not written by scene_to_json: sampling.placement and
/// sampling.binning, written as sampling.scheme (the name of their combination).
const std::vector<ParamSpec>& input_params();
const std::vector<MaterialSpec>& material_params();
const ParamSpec* find_param(const std::string& key);
const MaterialSpec* find_material_param(const std::string& key);
/// material.preset: the material preset (assets/materials/NAME.json) a surface starts from; not one of
/// material_params() (those are numbers in Material).
const ValueSpec& material_preset_param();

/// Sets material field `field` ("nu_db", "reflection_db", ...) from `value`; "preset" applies that preset's
/// values and records its name. `key` names the whole key path in errors.
void set_material(Material& m, const std::string& field, const json& value, const std::string& file,
                  const std::string& key);

/// "nu_db, q, mu, h_deg, reflection_db, ...": the material number keys, for error messages.
std::string material_keys_text();

/// Object keys (mesh, box, position, orientation_deg, scale, crease_angle_deg, phong_alpha, name): stage
/// Geometry (name: None).
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

/// A number as errors and allowed ranges print it ("0.5", "1e+06").
std::string number_text(double value);

/// Pixels of the sector (fan) image at its default height; validate_scene bounds it by kMaxImageCells.
double sector_image_pixels(const SonarParams& sonar);

/// Markdown table of all parameters (for docs and `sonarsim params`).
std::string params_markdown();

} // namespace sonarsim

// One row of the parameter table and its columns: key, unit, type, bounds, help, the stage a change
// invalidates, and the columns that feed the viewer (section, label, slider range) and the device presets
// (whether a preset may set it). The rows themselves are in scene/rows/*.cpp, the tables in params.hpp.
#pragma once
#include "core/data/scene.hpp"

#include <functional>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

namespace sonarsim {

using json = nlohmann::json;

enum class ParamType { Number, Integer, Vec3, Enum, Bool, String };

/// What must be recomputed when a parameter changes (each stage implies the ones after it).
/// Place: the stored hits stay valid, but the adaptive sampler placed its rays by a value that changed (a
/// `steers_sampler` row): a preview re-shades the hits it has, any other render re-traces
/// (Simulator::render), so that a full-quality image is the one a fresh render makes.
enum class Stage { Geometry = 0, Trace = 1, Place = 2, Shade = 3, Sensor = 4, Display = 5, None = 6 };

/// Where the viewer's controls panel shows a row (None: not in the viewer).
enum class Section { None, Pose, Sonar, Water, Material, Object, Display, Sensor, Sampling, Motion };

/// The panel's header of a section: "Sonar", "Object / material", ...
const char* section_title(Section section);

/// The values a slider sweeps; typing a value (Ctrl+click) still allows any value the row accepts.
struct SliderRange {
    double lo = 0, hi = 0;
    bool logarithmic = false;
};

/// A kind of sonar as a bit of ValueSpec::kinds.
constexpr unsigned kind_bit(SonarKind kind) {
    return 1u << unsigned(kind);
}
constexpr unsigned kAllKinds =
    kind_bit(SonarKind::Imaging) | kind_bit(SonarKind::Sidescan) | kind_bit(SonarKind::Scanning);

/// Chainable setters of the columns, shared by every kind of row: `number(...).steers().preset()`.
template <class Row> struct RowColumns {
    /// The adaptive sampler places its rays by this value (ValueSpec::steers_sampler).
    Row& steers() {
        return set([](Row& r) { r.steers_sampler = true; });
    }
    /// A device preset may set this value (ValueSpec::preset_may_set).
    Row& preset() {
        return set([](Row& r) { r.preset_may_set = true; });
    }
    Row& with_label(std::string text) {
        return set([&](Row& r) { r.label = std::move(text); });
    }
    Row& with_slider(double lo, double hi) {
        return set([&](Row& r) { r.slider = {lo, hi, false}; });
    }
    Row& with_log_slider(double lo, double hi) {
        return set([&](Row& r) { r.slider = {lo, hi, true}; });
    }
    Row& in_section(Section s) {
        return set([&](Row& r) { r.section = s; });
    }
    /// Only these kinds of sonar use the value (ValueSpec::kinds); a scene of another kind may not set it.
    Row& only_for(std::initializer_list<SonarKind> kinds) {
        return set([&](Row& r) {
            r.kinds = 0;
            for (SonarKind k : kinds) r.kinds |= kind_bit(k);
        });
    }

  private:
    template <class F> Row& set(F f) {
        Row& r = static_cast<Row&>(*this);
        f(r);
        return r;
    }
};

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
    /// between materials): under the adaptive scheme a change costs Stage::Place (a preview re-shades, a
    /// full image re-traces), otherwise `stage`.
    bool steers_sampler = false;
    /// A device preset (assets/devices/*.json) may set it; loading a preset that sets another key fails.
    bool preset_may_set = false;
    Section section = Section::None; ///< in the viewer's controls
    std::string label;               ///< the viewer's short name ("f frequency"); empty: from the key
    SliderRange slider;              ///< lo == hi: the row's bounds
    /// The kinds of sonar (sonar.kind) that use the value, as kind_bit()s: a scene of another kind keeps the
    /// row's default, and setting it otherwise is an error (validate_scene).
    unsigned kinds = kAllKinds;
    bool used_by(SonarKind kind) const { return (kinds & kind_bit(kind)) != 0; }
    /// What a change of this value recomputes in `scene` (the scene after the change).
    Stage effective_stage(const SceneDesc& scene) const;
    /// "label [unit]": `label`, or the key's last part without its unit suffix ("range max [m]").
    std::string label_text() const;
    /// `slider`, or the row's bounds when it has none.
    SliderRange slider_range() const;
};

/// A scene-level parameter with accessors into SceneDesc.
struct ParamSpec : ValueSpec, RowColumns<ParamSpec> {
    std::function<json(const SceneDesc&)> get;
    std::function<void(SceneDesc&, const json&)> put; ///< value already validated
    /// Sensor rows: the value sensor.model "ideal" sets (null: the model leaves it alone) and the one
    /// "device" sets when the device preset does not give one (null: leaves it alone).
    json ideal_value, device_value;
    ParamSpec& sensor_values(json ideal, json device) {
        ideal_value = std::move(ideal), device_value = std::move(device);
        return *this;
    }
};

/// A per-material parameter with accessors into Material. An optional one (reflection_db) is absent as
/// +infinity.
struct MaterialSpec : ValueSpec, RowColumns<MaterialSpec> {
    double Material::*field = nullptr;
    /// The field's value from a validated JSON value (null: absent).
    double value_of(const json& validated) const;
    /// The field as JSON (null when absent).
    json get(const Material& m) const;
    /// What changing the field from `before` to `after` in `scene` (after the change) invalidates: a mirror
    /// appearing or disappearing changes the traced paths, any other change the row's effective stage.
    Stage stage_of_change(double before, double after, const SceneDesc& scene) const;
};

/// Check `value` against `spec`; throws InputError(file, key_path, "... allowed ...") when it does not fit.
/// Returns the value in canonical form (integers as integers, vec3 as 3 numbers).
json validate_value(const ValueSpec& spec, const json& value, const std::string& file,
                    const std::string& key_path);

/// A key of one part of a scene (an object, the seafloor) with accessors into it. Its material's keys are
/// the material rows ("objects.N.material.q").
template <class Part> struct PartSpec : ValueSpec, RowColumns<PartSpec<Part>> {
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

} // namespace sonarsim

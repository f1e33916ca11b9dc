// The row builders of the parameter table (for scene/rows/*.cpp and params.cpp only): one generic field
// row with accessors through a reference into the scene, and its kinds (number, integer, vec3, enumeration,
// boolean, optional number; material and part rows), plus the rows of each table. A row's other columns
// are set by chaining (param_spec.hpp): `number(...).steers().preset().with_slider(1, 10)`.
#pragma once
#include "core/scene/params.hpp"

#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace sonarsim::rows {

using S = SceneDesc&;

/// A row of any kind with its common columns and no accessors yet.
template <class Row>
Row blank(std::string key, std::string unit, ParamType type, Stage stage, std::string help) {
    Row p;
    p.key = std::move(key), p.unit = std::move(unit), p.type = type, p.stage = stage,
    p.help = std::move(help);
    return p;
}

/// A row whose value is a T in the scene, reached through `ref`, stored as JSON of the same type.
template <class T>
ParamSpec field(std::string key, std::string unit, ParamType type, Stage stage, std::string help,
                std::function<T&(SceneDesc&)> ref) {
    auto p = blank<ParamSpec>(std::move(key), std::move(unit), type, stage, std::move(help));
    p.get = [ref](const SceneDesc& s) { return json(ref(const_cast<SceneDesc&>(s))); };
    p.put = [ref](SceneDesc& s, const json& v) { ref(s) = v.get<T>(); };
    return p;
}

/// Sets a row's bounds (exclusive where flagged).
template <class Row> Row bounded(Row p, double lo, double hi, bool lo_ex = false, bool hi_ex = false) {
    p.min = lo, p.max = hi, p.min_exclusive = lo_ex, p.max_exclusive = hi_ex;
    return p;
}

inline ParamSpec number(std::string key, std::string unit, double lo, double hi, bool lo_ex, bool hi_ex,
                        Stage stage, std::string help, std::function<double&(SceneDesc&)> ref) {
    return bounded(field<double>(std::move(key), std::move(unit), ParamType::Number, stage, std::move(help),
                                 std::move(ref)),
                   lo, hi, lo_ex, hi_ex);
}

/// A number that may be absent (null): std::optional in the scene.
inline ParamSpec optional_number(std::string key, std::string unit, double lo, double hi, Stage stage,
                                 std::string help, std::function<std::optional<double>&(SceneDesc&)> ref) {
    auto p = bounded(
        blank<ParamSpec>(std::move(key), std::move(unit), ParamType::Number, stage, std::move(help)), lo, hi);
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

inline ParamSpec integer(std::string key, double lo, double hi, Stage stage, std::string help,
                         std::function<int&(SceneDesc&)> ref) {
    return bounded(field<int>(std::move(key), "", ParamType::Integer, stage, std::move(help), std::move(ref)),
                   lo, hi);
}

inline ParamSpec vec3(std::string key, std::string unit, double lo, double hi, Stage stage, std::string help,
                      std::function<Vec3d&(SceneDesc&)> ref) {
    return bounded(field<Vec3d>(std::move(key), std::move(unit), ParamType::Vec3, stage, std::move(help),
                                std::move(ref)),
                   lo, hi);
}

inline ParamSpec boolean(std::string key, Stage stage, std::string help,
                         std::function<bool&(SceneDesc&)> ref) {
    return field<bool>(std::move(key), "", ParamType::Bool, stage, std::move(help), std::move(ref));
}

/// An enum stored by its name: choices[i] is the enumerator E(i).
template <class E>
ParamSpec enumeration(std::string key, std::vector<std::string> choices, Stage stage, std::string help,
                      std::function<E&(SceneDesc&)> ref) {
    auto p = blank<ParamSpec>(std::move(key), "", ParamType::Enum, stage, std::move(help));
    p.choices = std::move(choices);
    const auto names = p.choices;
    p.get = [ref, names](const SceneDesc& s) {
        return json(names.at(size_t(ref(const_cast<SceneDesc&>(s)))));
    };
    p.put = [ref, names](SceneDesc& s, const json& v) {
        for (size_t i = 0; i < names.size(); ++i)
            if (names[i] == v.get<std::string>()) ref(s) = E(i);
    };
    return p;
}

/// A material's number (stage Shade; the adaptive sampler refines by every material value).
inline MaterialSpec material(std::string key, std::string unit, double lo, double hi, bool lo_ex,
                             std::string help, double Material::*field) {
    auto m = blank<MaterialSpec>(std::move(key), std::move(unit), ParamType::Number, Stage::Shade,
                                 std::move(help));
    m.field = field, m.section = Section::Material;
    m.steers();
    return bounded(m, lo, hi, lo_ex);
}

/// A part's row without accessors (they follow).
template <class Part>
PartSpec<Part> part(std::string key, std::string unit, ParamType type, double lo, double hi, bool lo_ex,
                    Stage stage, std::string help) {
    return bounded(blank<PartSpec<Part>>(std::move(key), std::move(unit), type, stage, std::move(help)), lo,
                   hi, lo_ex);
}

// The rows of each table, in the order the table (and the docs) list them.
std::vector<ParamSpec> sonar_rows();          ///< rows/sonar.cpp: the device, pose, fan, levels
std::vector<ParamSpec> motion_rows();         ///< rows/sonar.cpp: motion during a frame, each its section
std::vector<ParamSpec> kind_rows();           ///< rows/kinds.cpp: side-scan and scanning sonars
std::vector<ParamSpec> water_rows();          ///< rows/water.cpp
std::vector<ParamSpec> sampling_rows();       ///< rows/sampling.cpp
std::vector<ParamSpec> sampling_input_rows(); ///< rows/sampling.cpp: read, not written (input_params)
std::vector<ParamSpec> display_rows();        ///< rows/display.cpp
std::vector<ParamSpec> sensor_rows();         ///< rows/sensor.cpp
std::vector<ParamSpec> export_rows();         ///< rows/display.cpp: the 8-bit exports' mapping, times
std::vector<MaterialSpec> material_rows();    ///< rows/material.cpp
ValueSpec material_preset_row();              ///< rows/material.cpp: material.preset
std::vector<ObjectSpec> object_rows();        ///< rows/parts.cpp
std::vector<SeafloorSpec> seafloor_rows();    ///< rows/parts.cpp

} // namespace sonarsim::rows

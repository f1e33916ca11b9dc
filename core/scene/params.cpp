// The tables of parameters assembled from their rows (scene/rows/*.cpp), each block in its viewer section,
// and their lookups by key.
#include "core/scene/params.hpp"

#include "core/base/errors.hpp"
#include "core/scene/materials.hpp"
#include "core/scene/param_rows.hpp"

namespace sonarsim {
namespace {

/// Appends `block` to `table`, its rows in `section` unless they name their own.
template <class Row> void append(std::vector<Row>& table, Section section, std::vector<Row> block) {
    for (Row& r : block) {
        if (r.section == Section::None) r.section = section;
        table.push_back(std::move(r));
    }
}

std::vector<ParamSpec> build_scene_params() {
    std::vector<ParamSpec> t;
    append(t, Section::Sonar, rows::sonar_rows());
    append(t, Section::None, rows::kind_rows());   // rows name their sections: the kind and its shape
    append(t, Section::None, rows::motion_rows()); // rows name their sections; batch's not in the viewer
    append(t, Section::Water, rows::water_rows());
    append(t, Section::Sampling, rows::sampling_rows());
    append(t, Section::Display, rows::display_rows());
    append(t, Section::Sensor, rows::sensor_rows());
    append(t, Section::None, rows::export_rows()); // the dataset's files: not in the viewer
    return t;
}

template <class Row> const Row* find_row(const std::vector<Row>& rows, const std::string& key) {
    for (auto& p : rows)
        if (p.key == key) return &p;
    return nullptr;
}

} // namespace

const std::vector<ParamSpec>& scene_params() {
    static const std::vector<ParamSpec> table = build_scene_params();
    return table;
}

const std::vector<ParamSpec>& input_params() {
    static const std::vector<ParamSpec> table = rows::sampling_input_rows();
    return table;
}

const std::vector<MaterialSpec>& material_params() {
    static const std::vector<MaterialSpec> table = rows::material_rows();
    return table;
}

const ValueSpec& material_preset_param() {
    static const ValueSpec row = rows::material_preset_row();
    return row;
}

const std::vector<ObjectSpec>& object_params() {
    static const std::vector<ObjectSpec> table = rows::object_rows();
    return table;
}

const std::vector<SeafloorSpec>& seafloor_params() {
    static const std::vector<SeafloorSpec> table = rows::seafloor_rows();
    return table;
}

const ParamSpec* find_param(const std::string& key) {
    if (const ParamSpec* p = find_row(scene_params(), key)) return p;
    return find_row(input_params(), key);
}

const MaterialSpec* find_material_param(const std::string& key) {
    return find_row(material_params(), key);
}

const ObjectSpec* find_object_param(const std::string& key) {
    return find_row(object_params(), key);
}

const SeafloorSpec* find_seafloor_param(const std::string& key) {
    return find_row(seafloor_params(), key);
}

std::string material_keys_text() {
    std::string keys;
    for (auto& p : material_params()) keys += (keys.empty() ? "" : ", ") + p.key;
    return keys;
}

void set_material(Material& m, const std::string& field, const json& value, const std::string& file,
                  const std::string& key) {
    if (field == material_preset_param().key) {
        const std::string name = validate_value(material_preset_param(), value, file, key).get<std::string>();
        if (const MaterialPreset* preset = find_material_preset(name))
            apply_material_preset(m, *preset);
        else
            m.preset = name; // "none": the values stay as they are
        return;
    }
    const MaterialSpec* spec = find_material_param(field);
    if (!spec) throw InputError(file, key, "unknown key; allowed: preset, " + material_keys_text());
    m.*(spec->field) = spec->value_of(validate_value(*spec, value, file, key));
}

} // namespace sonarsim

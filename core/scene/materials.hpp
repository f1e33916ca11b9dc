// Material presets: assets/materials/NAME.json, embedded in the library at build time (like the device
// presets), each a set of material values with their sources. `material.preset` of any surface applies one
// before the surface's explicit keys.
#pragma once
#include "core/data/scene.hpp"

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace sonarsim {

/// One value of a material preset: a material key ("nu_db"), its value and where it comes from.
struct MaterialValue {
    std::string key;
    nlohmann::json value;
    std::string source;
};

/// A source of a preset: the citation and what was taken or derived from it.
struct MaterialSource {
    std::string citation;
    std::string used_for;
};

struct MaterialPreset {
    std::string name;  ///< file name without .json: the value of material.preset
    std::string title; ///< e.g. "Medium sand (mean grain size 1.5 phi), Lambert fit at 100 kHz"
    std::string file;  ///< "assets/materials/NAME.json", for error messages
    std::vector<MaterialValue> values; ///< the keys it sets; every other key keeps its value
    std::vector<MaterialSource> sources;
    std::string notes; ///< what it leaves unset and why, and its limits
};

/// Reads a preset from its text: `file` (".../NAME.json") names it in errors and gives its name. Every value
/// must be a material row ("preset" excepted) with a valid value and a source, and the preset must cite at
/// least one source and carry notes; otherwise throws InputError naming the file and the key.
MaterialPreset parse_material_preset(const std::string& file, const std::string& text);

/// All presets, sorted by name, read once (a malformed one throws InputError).
const std::vector<MaterialPreset>& material_presets();

/// The preset called `name`, or nullptr ("none" and unknown names).
const MaterialPreset* find_material_preset(const std::string& name);

/// "none" followed by every preset's name: the values material.preset allows (from the embedded files'
/// names, without reading them).
std::vector<std::string> material_preset_choices();

/// Sets the preset's values in `m` (the other fields keep theirs) and records its name.
void apply_material_preset(Material& m, const MaterialPreset& preset);

} // namespace sonarsim

// Markdown table of every parameter, generated from the table (docs/parameters.md, `sonarsim params`), and
// the keys a device preset may set.
#include "core/scene/params.hpp"

#include <sstream>

namespace sonarsim {

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
    const ValueSpec& preset = material_preset_param();
    md << "| `material." << preset.key << "` | " << preset.unit << " | `" << json(m.preset).dump() << "` | "
       << cell(allowed_text(preset)) << " | " << cell(preset.help) << " |\n";
    for (auto& p : material_params())
        md << "| `material." << p.key << "` | " << p.unit << " | `" << p.get(m).dump() << "` | "
           << cell(allowed_text(p)) << " | " << cell(p.help) << " |\n";
    std::string preset_keys;
    for (auto& p : scene_params())
        if (p.preset_may_set) preset_keys += (preset_keys.empty() ? "`" : ", `") + p.key + "`";
    md << "\nA device preset (`assets/devices/NAME.json`, `sonar.device`) may set " << preset_keys
       << "; any other key is an error when the preset is read. A material preset "
          "(`assets/materials/NAME.json`, `material.preset`, `sonarsim materials`) may set any `material.*` "
          "number; its surface's explicit keys override it.\n";
    return md.str();
}

} // namespace sonarsim

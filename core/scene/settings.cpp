// Key routing: `key.path=value` from `--set`, the viewer and Python applied to a scene through the table
// (scene rows, materials of the water surface, the seafloor and the objects, object and seafloor rows),
// and the parsing of `--set`'s text.
#include "core/scene/params.hpp"

#include "core/base/errors.hpp"
#include "core/scene/scene_parts.hpp"

#include <cctype>
#include <filesystem>

namespace sonarsim {
namespace {

void set_value(SceneDesc& scene, const std::string& key, const json& value, const std::string& file) {
    if (auto* p = find_param(key)) {
        p->put(scene, validate_value(*p, value, file, key));
        apply_group_key(scene, key);
        return;
    }
    if (const std::optional<PartKey> part = part_key(scene, key, file)) {
        if (part->material) {
            Material* m = material_of(scene, part->part);
            if (!m) throw InputError(file, key, "the scene has no seafloor");
            set_material(*m, part->field, value, file, key);
            return;
        }
        if (part->part == kSeafloorPart) {
            if (const SeafloorSpec* p = find_seafloor_param(part->field)) {
                const json v = p->validated(value, file, key);
                if (!scene.seafloor) scene.seafloor = Seafloor{};
                p->put(*scene.seafloor, v, "");
                return;
            }
        } else if (part->part >= 0) {
            const ObjectSpec* p = find_object_param(part->field);
            if (!p)
                throw InputError(file, key,
                                 "unknown key; allowed: " + part_keys_text(object_params()) + ".*");
            // A mesh path given on the command line or in the viewer is relative to the working directory.
            std::error_code ec;
            p->put(scene.objects[size_t(part->part)], p->validated(value, file, key),
                   std::filesystem::current_path(ec).string());
            return;
        }
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

} // namespace sonarsim

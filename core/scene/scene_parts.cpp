#include "core/scene/scene_parts.hpp"

#include "core/base/errors.hpp"

namespace sonarsim {
namespace {

const std::string kSurfaceMaterialPrefix = "water.surface_material.", kSeafloorPrefix = "seafloor.",
                  kObjectsPrefix = "objects.", kMaterial = "material.";

} // namespace

std::string part_prefix(int part) {
    return part == kSurfacePart    ? std::string()
           : part == kSeafloorPart ? kSeafloorPrefix
                                   : kObjectsPrefix + std::to_string(part) + ".";
}

std::string material_prefix(int part) {
    return part == kSurfacePart ? kSurfaceMaterialPrefix : part_prefix(part) + kMaterial;
}

const Material* material_of(const SceneDesc& s, int part) {
    if (part == kSurfacePart) return &s.water.surface_material;
    if (part == kSeafloorPart) return s.seafloor ? &s.seafloor->material : nullptr;
    return part >= 0 && size_t(part) < s.objects.size() ? &s.objects[size_t(part)].material : nullptr;
}

Material* material_of(SceneDesc& s, int part) {
    return const_cast<Material*>(material_of(static_cast<const SceneDesc&>(s), part));
}

std::vector<int> material_parts(const SceneDesc& s) {
    std::vector<int> parts = {kSurfacePart};
    if (s.seafloor) parts.push_back(kSeafloorPart);
    for (size_t i = 0; i < s.objects.size(); ++i) parts.push_back(int(i));
    return parts;
}

std::optional<PartKey> part_key(const SceneDesc& s, const std::string& key, const std::string& file) {
    auto starts = [&](const std::string& prefix) { return key.rfind(prefix, 0) == 0; };
    auto below = [&](int part, const std::string& rest) {
        const bool material = rest.rfind(kMaterial, 0) == 0;
        return PartKey{part, material, material ? rest.substr(kMaterial.size()) : rest};
    };
    if (starts(kSurfaceMaterialPrefix))
        return PartKey{kSurfacePart, true, key.substr(kSurfaceMaterialPrefix.size())};
    if (starts(kSeafloorPrefix)) return below(kSeafloorPart, key.substr(kSeafloorPrefix.size()));
    if (!starts(kObjectsPrefix)) return std::nullopt;
    const std::string rest = key.substr(kObjectsPrefix.size());
    const size_t dot = rest.find('.');
    const std::string index = rest.substr(0, dot);
    size_t i = 0;
    if (index.empty() || index.find_first_not_of("0123456789") != std::string::npos || index.size() > 6 ||
        (i = std::stoul(index)) >= s.objects.size())
        throw InputError(file, key, "object index must be in [0, " + std::to_string(s.objects.size()) + ")");
    return below(int(i), dot == std::string::npos ? "" : rest.substr(dot + 1));
}

} // namespace sonarsim

// The scene's nested parts that keys address below the table's own rows: the water surface's material, the
// seafloor and its material, each object and its material. The one place their key prefixes are spelled and
// a key is routed to its part; `--set`, the viewer, stage tracking and the panels walk them from here.
#pragma once
#include "core/data/scene.hpp"

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace sonarsim {

/// The parts that own a material, numbered as the viewer's selection and the ground truth's ids: the water
/// surface, the seafloor, or an object's index (0, 1, ...).
constexpr int kSurfacePart = -2, kSeafloorPart = -1;

/// The key prefix of part p's material: "water.surface_material.", "seafloor.material.",
/// "objects.N.material.".
std::string material_prefix(int part);
/// The key prefix of part p's own rows: "seafloor.", "objects.N." ("" for the surface: its rows are water's).
std::string part_prefix(int part);

/// Part p's material; null when the scene has no such part (no seafloor, an index past the objects).
Material* material_of(SceneDesc& scene, int part);
const Material* material_of(const SceneDesc& scene, int part);

/// The parts that have a material, in key order: the surface, the seafloor (when there is one), each object.
std::vector<int> material_parts(const SceneDesc& scene);

/// A key below a part: the part and the rest of the key after its prefix ("objects.2.material.q" ->
/// {2, "q"} as a material key; "objects.2.position" -> {2, "position"} as an object key).
struct PartKey {
    int part = 0;
    bool material = false; ///< the key is one of the part's material's
    std::string field;     ///< the rest of the key
};
/// Routes `key` to its part; nullopt when it names none (a key of the table's own rows, or unknown). Throws
/// InputError(file, key) for an object index outside the scene's objects.
std::optional<PartKey> part_key(const SceneDesc& scene, const std::string& key, const std::string& file);

} // namespace sonarsim

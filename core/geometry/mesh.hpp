// Triangle meshes: loading (the formats of mesh_formats.hpp), boxes, and placement in the world.
// Shared, cached meshes: mesh_cache.hpp.
#pragma once
#include "core/meshfile/trimesh.hpp"
#include "core/data/scene.hpp"

#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace sonarsim {

/// Loads a mesh file by its format (mesh_formats.hpp). Throws InputError(file, key, ...) if it is missing,
/// unreadable, empty or malformed.
TriMesh load_mesh(const std::string& path, const std::string& scene_file, const std::string& key);

/// Axis-aligned box of size (dx, dy, dz) [m] centred on the origin, 12 outward-facing triangles.
TriMesh make_box(const Vec3d& size_m);

/// An object's placement, local -> world: scale, then rotate (R = Rz Ry Rx), then translate.
glm::dmat4 object_transform(const ObjectDesc& object);

/// Throws InputError(scene_file, key + ".scale", ...) when a placed point is beyond single precision.
void check_single_precision(const glm::dvec3& world, const std::string& scene_file, const std::string& key);

/// The mesh with every vertex mapped by `transform` (in double, rounded to float). Throws
/// InputError(scene_file, key + ".scale", ...) when a coordinate leaves single precision.
TriMesh transformed_mesh(const TriMesh& mesh, const glm::dmat4& transform, const std::string& scene_file,
                         const std::string& key);

/// Axis-aligned bounds of a mesh (min, max); returns false for an empty mesh.
bool mesh_bounds(const TriMesh& mesh, glm::vec3& lo, glm::vec3& hi);

} // namespace sonarsim

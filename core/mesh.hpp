// Triangle meshes: loading (OBJ/PLY/STL/OFF through OpenMesh), boxes, and placement in the world.
#pragma once
#include "scene.hpp"

#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace sonarsim {

struct TriMesh {
    std::vector<glm::vec3> vertices;
    std::vector<glm::uvec3> triangles;
};

/// Loads a mesh file. Throws InputError(file, key, ...) if it is missing, unreadable, empty or malformed.
TriMesh load_mesh(const std::string& path, const std::string& scene_file, const std::string& key);

/// Axis-aligned box of size (dx, dy, dz) [m] centred on the origin, 12 outward-facing triangles.
TriMesh make_box(const Vec3d& size_m);

/// World-space mesh of one object: load or build it, then scale, rotate (R = Rz Ry Rx) and translate.
TriMesh object_world_mesh(const ObjectDesc& object, const std::string& scene_file, const std::string& key);

/// Axis-aligned bounds of a mesh (min, max); returns false for an empty mesh.
bool mesh_bounds(const TriMesh& mesh, glm::vec3& lo, glm::vec3& hi);

} // namespace sonarsim

// A triangle mesh as read from a file: vertices and the triangles that index them (mesh_formats.hpp reads
// them; geometry/ places them in a scene).
#pragma once
#include <glm/glm.hpp>
#include <vector>

namespace sonarsim {

struct TriMesh {
    std::vector<glm::vec3> vertices;
    std::vector<glm::uvec3> triangles;
};

} // namespace sonarsim

// Smooth shading normals: per-corner normals of a mesh within a crease angle, computed once per mesh and
// crease angle and shared (like the mesh's BVH), interpolated at a hit with Embree's barycentric u, v.
#pragma once
#include "core/geometry/mesh.hpp"

#include <glm/glm.hpp>
#include <memory>
#include <vector>

namespace sonarsim {

/// A mesh's corner normals (local coordinates, unit length), three per triangle in the triangle's vertex
/// order. Empty: every triangle keeps its face normal (crease angle 0, or no two faces within the crease
/// angle share a vertex, as on a box).
struct ShadingNormals {
    std::shared_ptr<const TriMesh> mesh; ///< the mesh they belong to (kept alive: its address names it)
    double crease_angle_deg = 0;
    std::vector<glm::vec3> corner;
    /// per triangle (when smooth()): 1 when a corner normal differs from the face's normal, so that the
    /// face is part of a curved surface (phong_surface.hpp); 0 on a flat part or along a crease
    std::vector<unsigned char> bent;
    bool smooth() const { return !corner.empty(); }
    /// The shading normal at barycentric (u, v) of triangle `prim` (point = (1 - u - v) v0 + u v1 + v v2),
    /// not normalised; only when smooth().
    glm::vec3 at(unsigned prim, float u, float v) const {
        const glm::vec3* c = &corner[3 * size_t(prim)];
        return (1.0f - u - v) * c[0] + u * c[1] + v * c[2];
    }
};

/// Corner normals of `mesh` within `crease_angle_deg`: the normal at corner v of face f is the sum of the
/// unit normals of the faces g around the vertex (vertices welded by exact position) whose normal is within
/// the crease angle of f's (n_f . n_g >= cos crease), each weighted by g's angle at that corner
/// (Thuermer-Wuethrich, independent of how the surface is triangulated), normalised. Faces meeting at more
/// than the crease angle keep separate normals, so a box keeps its edges. Degenerate faces take no part.
/// `crease_angle_deg` <= 0: empty (face normals). Parallel (TBB); O(triangles x valence).
ShadingNormals corner_normals(const TriMesh& mesh, double crease_angle_deg);

/// corner_normals, computed once per (mesh, crease angle) while anything holds the result: every scene and
/// thread asking for the same mesh and angle shares one copy. Null for crease_angle_deg <= 0.
std::shared_ptr<const ShadingNormals> shared_corner_normals(const std::shared_ptr<const TriMesh>& mesh,
                                                            double crease_angle_deg);

} // namespace sonarsim

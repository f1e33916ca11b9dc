// The traceable scene: every object an Embree instance of its mesh's shared BVH, plus an analytic seafloor
// plane. First-hit queries against both; shadows come from the first hit.
#pragma once
#include "core/data/hits.hpp"
#include "core/geometry/mesh.hpp"
#include "core/data/scene.hpp"

#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace sonarsim {

/// Hits closer than this are ignored: a sonar touching a surface is not blocked by it [m].
constexpr double kMinHitRange_m = 1e-5;

struct Hit {
    /// range along the unit ray [m]; on a smooth object with `phong_alpha` > 0, where the ray meets its
    /// curved (Phong) surface (phong_surface.hpp)
    double t = 0;
    /// unit normal in world space (either side): the face's, or on a smooth object (crease_angle_deg) the
    /// shading normal interpolated from its corner normals
    glm::dvec3 normal{0};
    unsigned material = 0; ///< kFloorMaterial or object index + 1
    unsigned prim = 0;     ///< triangle index within its object (floor: 0)
    /// unit normal of the face hit, in world space (either side): the plane the hit point lies on (the
    /// adaptive sampler's continuity test, range footprints); equals `normal` unless the object is smooth.
    /// On a curved hit (`phong_alpha` > 0) the curved surface's normal at its point
    glm::dvec3 face_normal{0};
};

/// Objects as Embree instances. Each distinct mesh (one mesh cache entry; boxes by size) has one bottom-level
/// BVH, built once and shared by every object, SceneGeometry and thread that uses it; each object is an
/// instance of it with its own transform. Moving, turning or scaling objects only updates the instances'
/// transforms and re-commits the small top-level scene. One Embree device per process, created on first use.
/// Not thread-safe for writing: intersect() may run on many threads, but not during update_transforms().
class SceneGeometry {
  public:
    /// Gets every object's mesh from the mesh cache (only files not cached are read), builds the BVHs not
    /// built yet and the top-level scene. Throws InputError for a bad mesh or a placement beyond single
    /// precision.
    explicit SceneGeometry(const SceneDesc& scene);
    ~SceneGeometry();
    SceneGeometry(const SceneGeometry&) = delete;
    SceneGeometry& operator=(const SceneGeometry&) = delete;

    /// True when `scene` has the same shapes: as many objects, each with the same mesh file (resolved path)
    /// or box size. Then only poses differ, and update_transforms() can take them.
    bool same_shapes(const SceneDesc& scene) const;
    /// Places the objects as in `scene` (position, orientation, scale, crease angle, Phong alpha): new
    /// instance transforms, a re-commit of the top-level scene and, for a new crease angle, the mesh's shared
    /// corner normals for it (shading_normals.hpp); no file is read and no mesh BVH rebuilt. Returns false,
    /// changing nothing, when the shapes differ (same_shapes()). Throws InputError, changing nothing, when an
    /// object would leave single precision.
    bool update_transforms(const SceneDesc& scene);

    /// First hit of the ray o + t d, t in (0, t_max]; d must be unit length.
    std::optional<Hit> intersect(const glm::dvec3& origin, const glm::dvec3& dir, double t_max) const;

    size_t object_count() const;
    /// Object i's mesh in its own coordinates (shared with the mesh cache and other scenes).
    const std::shared_ptr<const TriMesh>& local_mesh(size_t i) const;
    /// Object i's placement: world = transform * (local, 1) (translate * rotate * scale).
    const glm::dmat4& object_transform(size_t i) const;
    /// Object i in world coordinates, computed on each call (for tests and tools; drawing uses
    /// local_mesh() and object_transform()).
    TriMesh world_mesh(size_t i) const;

    bool has_meshes() const;
    /// Bounds of all objects in world space (valid when has_meshes()): the placed boxes of their local
    /// bounds, so they may be a little larger than the meshes.
    glm::dvec3 bounds_lo() const;
    glm::dvec3 bounds_hi() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// First hit on the seafloor plane z = height (seen from either side), t in (0, t_max].
std::optional<Hit> intersect_floor(const Seafloor& floor, const glm::dvec3& origin, const glm::dvec3& dir,
                                   double t_max);

/// First hit on the water surface z = height from below (normal -z), t in (0, t_max].
std::optional<Hit> intersect_surface(double height_m, const glm::dvec3& origin, const glm::dvec3& dir,
                                     double t_max);

} // namespace sonarsim

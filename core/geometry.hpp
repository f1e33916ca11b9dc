// The traceable scene: triangle meshes in one Embree scene (built once per geometry change) plus an analytic
// seafloor plane. First-hit queries against both; shadows come from the first hit.
#pragma once
#include "mesh.hpp"
#include "scene.hpp"

#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace sonarsim {

/// Hits closer than this are ignored: a sonar touching a surface is not blocked by it [m].
constexpr double kMinHitRange_m = 1e-5;

/// Material index of the seafloor; object i has material index i + 1.
constexpr unsigned kFloorMaterial = 0;

struct Hit {
    double t = 0;          ///< range along the unit ray [m]
    glm::dvec3 normal{0};  ///< unit geometric normal (either side)
    unsigned material = 0; ///< kFloorMaterial or object index + 1
    unsigned prim = 0;     ///< triangle index within its object (floor: 0)
};

class SceneGeometry {
  public:
    /// Loads and places every object and builds the Embree scene. Throws InputError for bad meshes.
    explicit SceneGeometry(const SceneDesc& scene);
    ~SceneGeometry();
    SceneGeometry(const SceneGeometry&) = delete;
    SceneGeometry& operator=(const SceneGeometry&) = delete;

    /// First hit of the ray o + t d, t in (0, t_max]; d must be unit length.
    std::optional<Hit> intersect(const glm::dvec3& origin, const glm::dvec3& dir, double t_max) const;

    /// World-space meshes (for drawing and for tests).
    const std::vector<TriMesh>& meshes() const { return meshes_; }
    bool has_meshes() const { return scene_ != nullptr; }
    /// Bounds of all meshes (valid when has_meshes()).
    glm::dvec3 bounds_lo() const { return lo_; }
    glm::dvec3 bounds_hi() const { return hi_; }

  private:
    void release();
    std::string embree_error_; // first error reported by Embree's callback
    void* device_ = nullptr;   // RTCDevice
    void* scene_ = nullptr;    // RTCScene (null when there are no meshes)
    std::vector<TriMesh> meshes_;
    glm::dvec3 lo_{0}, hi_{0};
};

/// First hit on the seafloor plane z = height (seen from either side), t in (0, t_max].
std::optional<Hit> intersect_floor(const Seafloor& floor, const glm::dvec3& origin, const glm::dvec3& dir,
                                   double t_max);

} // namespace sonarsim

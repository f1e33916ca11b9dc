// Non-GL framing of the 3D view: each object's world bounds, which objects are terrain (never picked up by a
// plain drag), and the camera that frames the whole scene from an oblique view above (the default view, F).
#pragma once
#include "ui/model/camera.hpp"

#include "core/geometry/mesh.hpp"
#include "core/data/scene.hpp"

#include <glm/glm.hpp>
#include <memory>
#include <vector>

namespace sonarsim::ui {

struct Box3 {
    glm::dvec3 lo{0}, hi{0};
    glm::dvec3 size() const { return hi - lo; }
};

/// World bounds of a mesh placed by `transform` (local -> world): the placed corners of its local bounds.
Box3 placed_bounds(const TriMesh& local, const glm::dmat4& transform);
/// World bounds of every object (element i = object i), from its local mesh and its placement.
std::vector<Box3> object_bounds(const SceneDesc& scene,
                                const std::vector<std::shared_ptr<const TriMesh>>& local);

/// Horizontal extent [m] from which an object is terrain whatever the sonar's reach.
constexpr double kTerrainExtentM = 100.0;
/// Terrain: an object wider in both horizontal directions than twice the sonar's r_max or than
/// kTerrainExtentM (a bathymetry tile, a floor slab). A plain drag on it orbits even when it is selected.
bool is_terrain(const Box3& bounds, const SonarParams& sonar);

/// The camera of a new scene and of F: above and behind the sonar, off to starboard, looking down at about
/// 40 deg, at the nearest distance where the whole scene (the sonar, its field of view out to r_max, the
/// floor it sees and every object in `objects`) projects inside the central 86% of a viewport of aspect
/// w/h. Objects far larger than the sonar's reach (terrain) are framed only within kFrameReach x r_max of
/// the sonar, so the sonar and its frustum stay visible.
OrbitCamera default_camera(const SceneDesc& scene, const std::vector<Box3>& objects,
                           double aspect = 4.0 / 3.0);
/// Radius around the sonar (in r_max) within which terrain is framed.
constexpr double kFrameReach = 1.5;

} // namespace sonarsim::ui

// Non-GL geometry of the sonar in the world: its field-of-view shell, its housing, the elevation arc of an
// image pixel, and the mapping between sector-image pixels, (range, azimuth) and world points.
#pragma once
#include "core/display/image.hpp"
#include "core/geometry/mesh.hpp"
#include "core/data/scene.hpp"
#include "core/kinds/pings.hpp"
#include "core/sampling/trace.hpp"

#include <glm/glm.hpp>
#include <optional>
#include <memory>
#include <vector>

namespace sonarsim::ui {

/// World point at range r [m], azimuth a [deg], elevation e [deg] of the sonar.
glm::dvec3 sonar_point(const SonarParams& sonar, double range_m, double azimuth_deg, double elevation_deg);

/// The r_min..r_max shell of the azimuth x elevation field of view, in world coordinates.
struct FrustumShell {
    std::vector<glm::vec3> lines;     ///< wireframe: segment end points in pairs
    std::vector<glm::vec3> triangles; ///< faces: 3 vertices per triangle
};
FrustumShell frustum_shell(const SonarParams& sonar, int azimuth_steps = 16, int elevation_steps = 6);

/// Outline of the floor patch inside the field of view (the floor plane z = floor_z, within r_min..r_max):
/// segment end points in pairs, in world coordinates.
std::vector<glm::vec3> floor_footprint(const SonarParams& sonar, double floor_z, int steps = 48);

/// The fields of view to draw: the imaging sonar's fan; a side-scan's two beams (port, starboard) at the ping
/// heard from the sonar's pose, each a one-beam sonar at its transducer's pose, so that its floor footprint
/// is the swath; a scanning sonar's beam at the first step of its sector and at the head's newest step.
/// `along`: the pings heard along a played trajectory (ping_schedule_along; the newest at the sonar's pose),
/// or null: the scene's own (ping_schedule: the first at the sonar's pose).
std::vector<SonarParams> fields_of_view(const SceneDesc& scene, const std::vector<Ping>* along = nullptr);

/// The housing: a box behind the transducer face (front face at the sonar origin), in world coordinates.
TriMesh sonar_body(const SonarParams& sonar);

/// All points with range r and azimuth a over the elevation aperture (what one pixel cannot tell apart).
std::vector<glm::dvec3> elevation_arc(const SonarParams& sonar, double range_m, double azimuth_deg,
                                      int points = 48);

/// A place in the image: continuous range and azimuth, and the range bin and beam that hold it.
struct ImagePlace {
    double range_m = 0, azimuth_deg = 0;
    int bin = 0, beam = 0;
};
/// Range bin and beam of (r, a); false outside [r_min, r_max) x [-Theta/2, Theta/2].
bool polar_to_cell(const SonarParams& sonar, double range_m, double azimuth_deg, int& bin, int& beam);
/// Sector-image pixel (continuous, origin top-left) -> place; nullopt outside the fan.
std::optional<ImagePlace> sector_pixel_place(const SectorLayout& layout, const SonarParams& sonar, double px,
                                             double py);
/// Raw polar image (column = beam, row 0 at the top = farthest bin) pixel -> place.
std::optional<ImagePlace> polar_pixel_place(const SonarParams& sonar, double col, double row);

/// Where a world point appears in the image.
struct PointInImage {
    double range_m = 0, azimuth_deg = 0, elevation_deg = 0;
    int bin = 0, beam = 0;
    double px = 0, py = 0; ///< sector-image pixel (continuous)
    bool in_view = false;  ///< inside the range window, azimuth field of view and elevation aperture
};
PointInImage locate_world_point(const SonarParams& sonar, const SectorLayout& layout, const glm::dvec3& p);

/// Hit points of the traced cells whose echo lands (at least partly) in (bin, beam).
std::vector<glm::vec3> echoing_points(const TraceResult& hits, const SceneDesc& scene, int bin, int beam);

/// Every object's mesh in its own coordinates (object i -> element i; meshes from the mesh cache, boxes
/// built), for SceneRenderer::set_meshes. Throws InputError for a bad mesh or a placement beyond single
/// precision.
std::vector<std::shared_ptr<const TriMesh>> object_meshes(const SceneDesc& scene);

} // namespace sonarsim::ui

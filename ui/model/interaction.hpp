// Non-GL picking and dragging in the 3D view: which scene surface a mouse ray hits and how a drag of the
// frustum changes the sonar pose.
#pragma once
#include "ui/model/camera.hpp"
#include "core/geometry/geometry.hpp"
#include "core/data/scene.hpp"

#include <glm/glm.hpp>
#include <optional>
#include <vector>

namespace sonarsim::ui {

/// Nearest t > 0 at which the ray meets a triangle (a, b, c) (both sides), or nullopt.
std::optional<double> ray_triangle(const Ray& ray, const glm::dvec3& a, const glm::dvec3& b,
                                   const glm::dvec3& c);

/// First scene surface the ray meets: an object mesh or the seafloor.
struct SurfaceHit {
    glm::dvec3 point{0};
    double t = 0;
    unsigned material = 0; ///< kFloorMaterial (0) or object index + 1
};
std::optional<SurfaceHit> pick_surface(const Ray& ray, const SceneGeometry& geometry,
                                       const std::optional<Seafloor>& floor);

/// How a drag of the frustum moves the sonar.
enum class DragMode {
    Translate, ///< on the horizontal plane through the grabbed point (x, y)
    Vertical,  ///< up and down (z), on the vertical plane through the grabbed point facing the camera
    YawPitch,  ///< horizontal mouse motion turns (yaw), vertical motion tilts (pitch)
    Roll,      ///< horizontal mouse motion rolls
};

struct FrustumDrag {
    DragMode mode = DragMode::Translate;
    Pose start_pose;
    glm::dvec3 grab{0};     ///< world point grabbed [m]
    glm::dvec3 plane_n{0};  ///< normal of the drag plane (translate / vertical)
    glm::dvec2 start_px{0}; ///< mouse position at the start [px]
    /// What one pixel of the view covers at the grabbed point's depth [m] (0: no limit). A translation
    /// moves at most kMaxDragStretch times that per pixel of mouse motion, so a drag across a plane seen at
    /// a grazing angle moves the sonar by what the cursor covers, not to the horizon.
    double metres_per_px = 0;
    /// What the mouse's motion is multiplied by: 1, or kFineDrag while a fine modifier was held at the start.
    double fine = 1;
};

/// A fine drag (Alt on the sonar in 3D, Shift on a slider) moves and turns a tenth as much per pixel.
constexpr double kFineDrag = 0.1;

/// A translation keeps the grabbed point under the cursor while the drag plane is seen at 30 deg or more;
/// flatter, it moves this many times what a pixel covers at the grabbed point's depth, per pixel.
constexpr double kMaxDragStretch = 2.0;

/// What a pixel of a viewport `view_h_px` tall covers at distance `t_m` along `ray` from the camera [m].
double metres_per_px(const OrbitCamera& camera, const Ray& ray, double t_m, double view_h_px);

/// Degrees of rotation per pixel of mouse motion.
constexpr double kDegPerPixel = 0.25;

FrustumDrag begin_drag(DragMode mode, const Pose& pose, const Ray& ray, double t_grab,
                       const glm::dvec2& mouse_px, double metres_per_px = 0);
/// The pose for the mouse now at `mouse_px` with ray `ray`; angles stay within [-180, 180] (pitch [-90, 90]).
Pose drag_pose(const FrustumDrag& drag, const Ray& ray, const glm::dvec2& mouse_px);

} // namespace sonarsim::ui

// The 3D view's input state machine, GL-free: camera orbit / pan / zoom, picking, and the drags that edit the
// scene (the sonar by its handles, the selected object by its surface; a drag elsewhere orbits). Fed one
// InputEvent at a time in the order they happened, so a quick click (press and release inside one frame) is a
// click, and mouse motion made before a press never counts as a drag. Unit-tested with synthetic event
// sequences (tests/ui/test_view_controller.cpp).
#pragma once
#include "ui/model/camera.hpp"
#include "ui/model/input_events.hpp"
#include "ui/model/interaction.hpp"
#include "ui/model/layout.hpp"

#include "core/geometry/geometry.hpp"
#include "core/data/scene.hpp"

#include <glm/glm.hpp>
#include <optional>
#include <vector>

namespace sonarsim::ui {

/// What the controller sees of the rest of the viewer for one event.
struct ViewContext {
    const SceneDesc& scene;
    const SceneGeometry& geometry;
    Rect view;                 ///< the 3D view in window pixels
    bool ui_has_mouse = false; ///< a panel, menu or popup takes presses and the wheel
};

/// Mouse motion [px] from the press before a press becomes a drag (below it, it is a click).
constexpr double kClickSlopPx = 3.0;
/// Pick radius of the frustum's handles on screen [px].
constexpr double kHandlePickPx = 10.0;
/// Scale factor per pixel of vertical motion of an Alt-drag on an object (up grows).
constexpr double kScalePerPixel = 0.01;

/// Where the sonar can be grabbed besides its housing: on the boresight at r_min, the near end of the
/// field of view (the blind zone in front of the sonar, where objects seldom are).
std::vector<glm::dvec3> frustum_handles(const SceneDesc& scene);

/// Which drag a press with these modifiers starts on the sonar or an object (Alt does not choose one: it
/// makes a sonar's drag fine, and scales an object when held alone).
DragMode drag_mode_for(int mods);

/// ViewController::selected before anything is clicked: a drag anywhere but on the sonar orbits.
constexpr int kNothingSelected = -3;

class ViewController {
  public:
    enum class Grab { None, Orbit, Pan, Frustum, Object };

    OrbitCamera camera;
    /// Object whose material and placement the panel edits; -1 = seafloor; kNothingSelected at start.
    int selected = kNothingSelected;

    /// Handles one event. Returns the edited scene when the event changed it (a frustum or object drag).
    std::optional<SceneDesc> handle(const InputEvent& e, const ViewContext& ctx);
    /// Hover feedback for the mouse at rest at `mouse`: the frustum handle under it, the surface point.
    void hover(const glm::dvec2& mouse, const ViewContext& ctx);

    /// The gesture held now (None before the press has moved kClickSlopPx for a pending grab).
    Grab grab() const { return moved_ ? grab_ : Grab::None; }
    /// A press is held (whatever it will become).
    bool pressed() const { return grab_ != Grab::None; }
    /// True while the press edits the scene (frustum or object).
    bool editing_scene() const { return grab_ == Grab::Frustum || grab_ == Grab::Object; }
    /// True once after a drag that edited the scene ended: one undo step.
    bool take_edit_finished();

    bool sonar_hot() const { return sonar_hot_; }
    const std::optional<glm::dvec3>& surface_hover() const { return surface_hover_; }

  private:
    void press(const InputEvent& e, const ViewContext& ctx, const Ray& ray);
    std::optional<SceneDesc> drag(const InputEvent& e, const ViewContext& ctx, const Ray& ray);
    void release(const InputEvent& e, const ViewContext& ctx);
    /// A press on `object` with modifiers `mods` drags it: it is the selected one, and terrain
    /// (is_terrain) only with a modifier. Otherwise the press orbits, and a click selects.
    bool object_drag_allowed(int object, int mods, const ViewContext& ctx) const;

    Grab grab_ = Grab::None;
    int grab_button_ = 0;
    bool moved_ = false, edit_finished_ = false;
    glm::dvec2 press_px_{0}, last_px_{0};
    std::optional<SurfaceHit> press_hit_;
    FrustumDrag drag_; ///< frustum, or an object's position/orientation as a pose
    int object_ = -1;  ///< object being dragged
    bool scaling_ = false;
    Vec3d start_scale_{1, 1, 1};
    bool sonar_hot_ = false;
    std::optional<glm::dvec3> surface_hover_;
};

/// Nearest pick of the sonar by its handles (housing or the far-edge handle); nullopt on a miss. The frustum
/// shell itself is not a handle, so objects inside the field of view stay pickable.
std::optional<double> pick_sonar_handle(const Ray& ray, const SceneDesc& scene, const OrbitCamera& camera,
                                        const Rect& view, const glm::dvec2& mouse_px);

} // namespace sonarsim::ui

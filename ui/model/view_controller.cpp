#include "ui/model/view_controller.hpp"

#include "ui/model/framing.hpp"
#include "ui/model/sonar_geometry.hpp"

#include <algorithm>
#include <cmath>

namespace sonarsim::ui {

std::vector<glm::dvec3> frustum_handles(const SceneDesc& scene) {
    return {sonar_point(scene.sonar, scene.sonar.range_min_m, 0, 0)};
}

DragMode drag_mode_for(int m) {
    const bool ctrl = m & mods::Control, shift = m & mods::Shift;
    if (ctrl && shift) return DragMode::Roll;
    if (ctrl) return DragMode::YawPitch;
    if (shift) return DragMode::Vertical;
    return DragMode::Translate;
}

std::optional<double> pick_sonar_handle(const Ray& ray, const SceneDesc& scene, const OrbitCamera& camera,
                                        const Rect& view, const glm::dvec2& mouse_px) {
    const SonarParams& sonar = scene.sonar;
    std::optional<double> best;
    const TriMesh body = sonar_body(sonar);
    for (auto& t : body.triangles)
        if (auto h = ray_triangle(ray, body.vertices[t.x], body.vertices[t.y], body.vertices[t.z]))
            if (!best || *h < *best) best = h;
    for (const glm::dvec3& p : frustum_handles(scene)) {
        glm::dvec2 px;
        if (!camera.project(p, int(view.w), int(view.h), px)) continue;
        if (glm::length(px + glm::dvec2(view.x, view.y) - mouse_px) > kHandlePickPx) continue;
        const double t = glm::dot(p - ray.origin, ray.dir);
        if (t > 0 && (!best || t < *best)) best = t;
    }
    return best;
}

namespace {
Ray ray_at(const OrbitCamera& cam, const Rect& v, const glm::dvec2& m) {
    return cam.ray_through(m.x - v.x, m.y - v.y, int(v.w), int(v.h));
}
} // namespace

std::optional<SceneDesc> ViewController::handle(const InputEvent& e, const ViewContext& ctx) {
    const Ray ray = ray_at(camera, ctx.view, e.pos);
    const bool inside = ctx.view.contains(e.pos.x, e.pos.y) && !ctx.ui_has_mouse;
    switch (e.type) {
    case InputEvent::Type::Press:
        if (grab_ == Grab::None && inside) press(e, ctx, ray);
        return std::nullopt;
    case InputEvent::Type::Move:
        return drag(e, ctx, ray);
    case InputEvent::Type::Release:
        if (grab_ != Grab::None && e.button == grab_button_) release(e, ctx);
        return std::nullopt;
    case InputEvent::Type::Wheel:
        if (inside && grab_ == Grab::None) camera.zoom(e.wheel);
        return std::nullopt;
    case InputEvent::Type::Key:
        return std::nullopt;
    }
    return std::nullopt;
}

void ViewController::press(const InputEvent& e, const ViewContext& ctx, const Ray& ray) {
    grab_button_ = e.button;
    press_px_ = last_px_ = e.pos;
    moved_ = false;
    press_hit_.reset();
    if (e.button != button::Left) {
        grab_ = Grab::Pan;
        return;
    }
    const SceneDesc& s = ctx.scene;
    const auto sonar_t = pick_sonar_handle(ray, s, camera, ctx.view, e.pos);
    press_hit_ = pick_surface(ray, ctx.geometry, s.seafloor);
    if (sonar_t && (!press_hit_ || *sonar_t <= press_hit_->t)) {
        grab_ = Grab::Frustum;
        drag_ = begin_drag(drag_mode_for(e.mods), s.sonar.pose, ray, *sonar_t, e.pos,
                           metres_per_px(camera, ray, *sonar_t, ctx.view.h));
        if (e.mods & mods::Alt) drag_.fine = kFineDrag;
        press_hit_.reset();
        return;
    }
    if (press_hit_ && press_hit_->material != kFloorMaterial &&
        object_drag_allowed(int(press_hit_->material) - 1, e.mods, ctx)) {
        object_ = int(press_hit_->material) - 1;
        const ObjectDesc& o = s.objects[size_t(object_)];
        grab_ = Grab::Object;
        scaling_ = (e.mods & mods::Alt) && !(e.mods & (mods::Control | mods::Shift));
        start_scale_ = o.scale;
        const Pose as_pose{o.position_m, o.orientation_deg};
        drag_ = begin_drag(drag_mode_for(e.mods), as_pose, ray, press_hit_->t, e.pos,
                           metres_per_px(camera, ray, press_hit_->t, ctx.view.h));
        if ((e.mods & mods::Alt) && !scaling_) drag_.fine = kFineDrag; // Alt with Shift or Ctrl
        return;
    }
    grab_ = Grab::Orbit;
}

bool ViewController::object_drag_allowed(int object, int m, const ViewContext& ctx) const {
    // Hands first: a drag orbits unless it starts on the selected object, and terrain (which fills the
    // view) moves only with a modifier held.
    if (object != selected || object < 0 || size_t(object) >= ctx.scene.objects.size() ||
        size_t(object) >= ctx.geometry.object_count())
        return false;
    if (m & (mods::Control | mods::Shift | mods::Alt)) return true;
    const auto& mesh = ctx.geometry.local_mesh(size_t(object));
    return !mesh ||
           !is_terrain(placed_bounds(*mesh, ctx.geometry.object_transform(size_t(object))), ctx.scene.sonar);
}

std::optional<SceneDesc> ViewController::drag(const InputEvent& e, const ViewContext& ctx, const Ray& ray) {
    if (grab_ == Grab::None) return std::nullopt;
    if (!moved_ && glm::length(e.pos - press_px_) < kClickSlopPx) return std::nullopt;
    moved_ = true;
    const glm::dvec2 d = e.pos - last_px_;
    last_px_ = e.pos;
    switch (grab_) {
    case Grab::Orbit:
        camera.orbit(d.x, d.y);
        return std::nullopt;
    case Grab::Pan:
        camera.pan(d.x, d.y, int(ctx.view.h));
        return std::nullopt;
    case Grab::Frustum: {
        SceneDesc s = ctx.scene;
        s.sonar.pose = drag_pose(drag_, ray, e.pos);
        return s;
    }
    case Grab::Object: {
        if (object_ < 0 || size_t(object_) >= ctx.scene.objects.size()) return std::nullopt;
        SceneDesc s = ctx.scene;
        ObjectDesc& o = s.objects[size_t(object_)];
        if (scaling_) {
            const double k = std::exp(-(e.pos.y - press_px_.y) * kScalePerPixel);
            for (int i = 0; i < 3; ++i) o.scale[size_t(i)] = start_scale_[size_t(i)] * k;
        } else {
            const Pose p = drag_pose(drag_, ray, e.pos);
            o.position_m = p.position_m;
            o.orientation_deg = p.orientation_deg;
        }
        return s;
    }
    case Grab::None:
        break;
    }
    return std::nullopt;
}

void ViewController::release(const InputEvent&, const ViewContext& ctx) {
    if (!moved_ && grab_ != Grab::Frustum && grab_ != Grab::Pan && press_hit_) {
        // A click: select the object under the mouse (the floor selects the seafloor's material).
        selected = press_hit_->material == kFloorMaterial ? -1 : int(press_hit_->material) - 1;
        if (selected < 0 && !ctx.scene.seafloor) selected = 0;
    }
    if (moved_ && editing_scene()) edit_finished_ = true;
    if (grab_ == Grab::Object && !moved_) selected = object_;
    grab_ = Grab::None;
    moved_ = false;
    scaling_ = false;
    object_ = -1;
}

bool ViewController::take_edit_finished() {
    const bool f = edit_finished_;
    edit_finished_ = false;
    return f;
}

void ViewController::hover(const glm::dvec2& mouse, const ViewContext& ctx) {
    sonar_hot_ = grab_ == Grab::Frustum;
    surface_hover_.reset();
    if (grab_ != Grab::None || !ctx.view.contains(mouse.x, mouse.y) || ctx.ui_has_mouse) return;
    const Ray ray = ray_at(camera, ctx.view, mouse);
    sonar_hot_ = pick_sonar_handle(ray, ctx.scene, camera, ctx.view, mouse).has_value();
    if (auto hit = pick_surface(ray, ctx.geometry, ctx.scene.seafloor)) surface_hover_ = hit->point;
}

} // namespace sonarsim::ui

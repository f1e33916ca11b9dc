// The 3D view's state machine fed synthetic event sequences: quick clicks, drags of the camera, the sonar
// by its handles and objects by their surfaces, and what counts as one edit.
#include "ui/model/sonar_geometry.hpp"
#include "ui/model/view_controller.hpp"

#include "core/scene/scene_io.hpp"

#include <catch2/catch.hpp>

using namespace sonarsim;
using namespace sonarsim::ui;

namespace {

struct Rig {
    SceneDesc scene = default_scene();
    SceneGeometry geometry{scene};
    ViewController c;
    Rect view{300, 20, 600, 500};
    Rig() {
        c.camera.target = {1.2, 1.8, 0.1};
        c.camera.distance_m = 4;
        c.camera.azimuth_deg = -60;
        c.camera.elevation_deg = 40;
    }
    ViewContext ctx(bool ui = false) const { return {scene, geometry, view, ui}; }
    /// Feeds an event; applies a returned edit as the viewer does.
    void feed(InputEvent::Type t, glm::dvec2 p, int b = button::Left, int m = 0) {
        InputEvent e;
        e.type = t, e.pos = p, e.button = b, e.mods = m;
        if (auto next = c.handle(e, ctx())) {
            scene = *next;
            geometry.update_transforms(scene);
        }
    }
    /// Window pixel where world point w appears.
    glm::dvec2 pixel_of(const glm::dvec3& w) const {
        glm::dvec2 px;
        REQUIRE(c.camera.project(w, int(view.w), int(view.h), px));
        return px + glm::dvec2(view.x, view.y);
    }
};

bool same_camera(const OrbitCamera& a, const OrbitCamera& b) {
    return a.azimuth_deg == b.azimuth_deg && a.elevation_deg == b.elevation_deg && a.target == b.target &&
           a.distance_m == b.distance_m;
}

using T = InputEvent::Type;

} // namespace

TEST_CASE("a quick click after fast motion from the panel does not move the camera", "[ui][controller]") {
    Rig r;
    const OrbitCamera before = r.c.camera;
    // The mouse comes from the left panel (x = 50) and clicks in the empty water above the floor, all within
    // one frame: the 550 px of motion before the press must not count as a drag.
    r.feed(T::Move, {50, 100});
    r.feed(T::Move, {600, 60});
    r.feed(T::Press, {600, 60});
    r.feed(T::Release, {600, 60});
    CHECK(same_camera(r.c.camera, before));
    CHECK(r.c.grab() == ViewController::Grab::None);
    CHECK_FALSE(r.c.pressed());
    CHECK_FALSE(r.c.take_edit_finished());
}

TEST_CASE("a press that moves less than the click slop is a click", "[ui][controller]") {
    Rig r;
    const OrbitCamera before = r.c.camera;
    r.feed(T::Press, {600, 60});
    r.feed(T::Move, {602, 61});
    r.feed(T::Release, {602, 61});
    CHECK(same_camera(r.c.camera, before));
}

TEST_CASE("an orbit drag turns the camera by the motion after the press only", "[ui][controller]") {
    Rig r;
    const OrbitCamera before = r.c.camera;
    r.feed(T::Move, {100, 100}); // before the press: ignored
    r.feed(T::Press, {600, 60});
    r.feed(T::Move, {620, 60});
    r.feed(T::Move, {640, 60});
    CHECK(r.c.grab() == ViewController::Grab::Orbit);
    r.feed(T::Release, {640, 60});
    OrbitCamera expected = before;
    expected.orbit(40, 0);
    CHECK(r.c.camera.azimuth_deg == Approx(expected.azimuth_deg));
    CHECK(r.c.camera.elevation_deg == Approx(before.elevation_deg));
    CHECK_FALSE(r.c.take_edit_finished()); // the camera is not part of the scene
}

TEST_CASE("presses over a panel or outside the view are ignored", "[ui][controller]") {
    Rig r;
    const OrbitCamera before = r.c.camera;
    InputEvent e;
    e.type = T::Press, e.pos = {600, 60};
    r.c.handle(e, r.ctx(true));
    e.type = T::Move, e.pos = {700, 90};
    r.c.handle(e, r.ctx(true));
    CHECK(same_camera(r.c.camera, before));
    r.feed(T::Press, {100, 60}); // left of the view
    r.feed(T::Move, {700, 90});
    CHECK(same_camera(r.c.camera, before));
}

TEST_CASE("clicking the prism inside the frustum selects it and dragging moves it", "[ui][controller]") {
    Rig r;
    r.c.selected = -1;
    const glm::dvec3 top(1.5, 1.5, 0.22); // the prism's top face centre (inside the field of view)
    const glm::dvec2 p = r.pixel_of(top);
    r.feed(T::Move, p);
    r.feed(T::Press, p);
    r.feed(T::Release, p);
    CHECK(r.c.selected == 0);
    CHECK(r.scene.objects[0].position_m == default_scene().objects[0].position_m);

    // Drag it: the grabbed point follows the mouse on the horizontal plane through it.
    const glm::dvec2 q = r.pixel_of(top + glm::dvec3(0.2, -0.1, 0));
    r.feed(T::Press, p);
    r.feed(T::Move, (p + q) / 2.0);
    r.feed(T::Move, q);
    CHECK(r.c.editing_scene());
    r.feed(T::Release, q);
    CHECK(r.scene.objects[0].position_m[0] == Approx(1.7).margin(1e-6));
    CHECK(r.scene.objects[0].position_m[1] == Approx(1.4).margin(1e-6));
    CHECK(r.scene.objects[0].position_m[2] == Approx(0.11).margin(1e-9));
    CHECK(r.c.take_edit_finished());
    CHECK_FALSE(r.c.take_edit_finished()); // once per drag
}

TEST_CASE("Alt-dragging an object up scales it, Ctrl-dragging turns it", "[ui][controller]") {
    Rig r;
    const glm::dvec2 p = r.pixel_of({1.5, 1.5, 0.22});
    r.feed(T::Press, p); // a click selects it
    r.feed(T::Release, p);
    REQUIRE(r.c.selected == 0);
    r.feed(T::Press, p, button::Left, mods::Alt);
    r.feed(T::Move, p + glm::dvec2(0, -50));
    r.feed(T::Release, p + glm::dvec2(0, -50));
    for (double s : r.scene.objects[0].scale) CHECK(s == Approx(std::exp(50 * kScalePerPixel)));
    r.feed(T::Press, p, button::Left, mods::Control);
    r.feed(T::Move, p + glm::dvec2(40, 0));
    r.feed(T::Release, p + glm::dvec2(40, 0));
    CHECK(r.scene.objects[0].orientation_deg[2] == Approx(-40 * kDegPerPixel));
}

TEST_CASE("the sonar is grabbed by its handle and moves, objects keep still", "[ui][controller]") {
    Rig r;
    const glm::dvec3 h = frustum_handles(r.scene)[0];
    const glm::dvec2 p = r.pixel_of(h);
    r.c.hover(p, r.ctx());
    CHECK(r.c.sonar_hot());
    const Pose before = r.scene.sonar.pose;
    r.feed(T::Press, p);
    r.feed(T::Move, p + glm::dvec2(30, 0));
    CHECK(r.c.grab() == ViewController::Grab::Frustum);
    r.feed(T::Release, p + glm::dvec2(30, 0));
    CHECK(r.scene.sonar.pose.position_m != before.position_m);
    CHECK(r.scene.sonar.pose.position_m[2] == Approx(before.position_m[2]));
    CHECK(r.scene.objects[0].position_m == default_scene().objects[0].position_m);
    CHECK(r.c.take_edit_finished());
}

TEST_CASE("drag modes follow the modifiers", "[ui][controller]") {
    CHECK(drag_mode_for(0) == DragMode::Translate);
    CHECK(drag_mode_for(mods::Shift) == DragMode::Vertical);
    CHECK(drag_mode_for(mods::Control) == DragMode::YawPitch);
    CHECK(drag_mode_for(mods::Control | mods::Shift) == DragMode::Roll);
    CHECK(drag_mode_for(mods::Alt) == DragMode::Translate); // Alt: fine, not another drag
    CHECK(drag_mode_for(mods::Alt | mods::Control) == DragMode::YawPitch);
}

TEST_CASE("Alt makes a drag of the sonar fine: a tenth of the move and of the turn", "[ui][controller]") {
    for (const int m : {0, int(mods::Control)}) {
        INFO(m);
        Rig plain, fine;
        const glm::dvec2 p = plain.pixel_of(frustum_handles(plain.scene)[0]);
        const glm::dvec2 path[] = {p, p + glm::dvec2(20, 0), p + glm::dvec2(40, -10)};
        for (Rig* r : {&plain, &fine}) {
            const int held = r == &plain ? m : m | mods::Alt;
            r->feed(T::Press, path[0], button::Left, held);
            r->feed(T::Move, path[1], button::Left, held);
            r->feed(T::Move, path[2], button::Left, held);
            r->feed(T::Release, path[2], button::Left, held);
        }
        const Pose start = default_scene().sonar.pose;
        const Pose &a = plain.scene.sonar.pose, &b = fine.scene.sonar.pose;
        for (size_t i = 0; i < 3; ++i) {
            CHECK(b.position_m[i] - start.position_m[i] ==
                  Approx(kFineDrag * (a.position_m[i] - start.position_m[i])).margin(1e-9));
            CHECK(b.orientation_deg[i] - start.orientation_deg[i] ==
                  Approx(kFineDrag * (a.orientation_deg[i] - start.orientation_deg[i])).margin(1e-9));
        }
        CHECK(std::abs(a.position_m[0] - start.position_m[0]) +
                  std::abs(a.orientation_deg[2] - start.orientation_deg[2]) >
              0.01);
    }
}

TEST_CASE("the wheel zooms only inside the view", "[ui][controller]") {
    Rig r;
    const double d = r.c.camera.distance_m;
    InputEvent e;
    e.type = T::Wheel, e.pos = {600, 200}, e.wheel = 1;
    r.c.handle(e, r.ctx());
    CHECK(r.c.camera.distance_m == Approx(d * 0.88));
    e.pos = {100, 200};
    r.c.handle(e, r.ctx());
    CHECK(r.c.camera.distance_m == Approx(d * 0.88));
}

TEST_CASE("the housing and the handle are grabbable and the field of view shell is not", "[ui][controller]") {
    Rig r;
    glm::dvec3 body(0);
    const TriMesh housing = sonar_body(r.scene.sonar);
    for (const auto& p : housing.vertices) body += glm::dvec3(p) / double(housing.vertices.size());
    r.c.hover(r.pixel_of(body), r.ctx());
    CHECK(r.c.sonar_hot());
    r.c.hover(r.pixel_of(frustum_handles(r.scene)[0]), r.ctx());
    CHECK(r.c.sonar_hot());
    // Inside the field of view, in open water, away from both handles: not the sonar.
    r.c.hover(r.pixel_of(sonar_point(r.scene.sonar, 1.2, 8, 3)), r.ctx());
    CHECK_FALSE(r.c.sonar_hot());
}

TEST_CASE("a plain drag on an unselected object orbits; a click selects it, then a drag moves it",
          "[ui][controller]") {
    Rig r;
    REQUIRE(r.c.selected == kNothingSelected); // at start: a drag anywhere but on the sonar orbits
    const glm::dvec2 p = r.pixel_of({1.5, 1.5, 0.22});
    const OrbitCamera before = r.c.camera;
    for (const int selected : {kNothingSelected, -1}) { // nothing, then the seafloor
        r.c.selected = selected, r.c.camera = before;
        r.feed(T::Press, p);
        r.feed(T::Move, p + glm::dvec2(20, 0));
        r.feed(T::Move, p + glm::dvec2(40, 0));
        CHECK(r.c.grab() == ViewController::Grab::Orbit);
        r.feed(T::Release, p + glm::dvec2(40, 0));
        OrbitCamera expected = before;
        expected.orbit(40, 0);
        CHECK(r.c.camera.azimuth_deg == Approx(expected.azimuth_deg));
        CHECK(r.scene.objects[0].position_m == default_scene().objects[0].position_m);
        CHECK(r.c.selected == selected); // a drag is not a click
        CHECK_FALSE(r.c.take_edit_finished());
    }

    r.c.camera = before;
    r.feed(T::Press, p);
    r.feed(T::Release, p);
    CHECK(r.c.selected == 0);
    r.feed(T::Press, p);
    r.feed(T::Move, p + glm::dvec2(40, 0));
    CHECK(r.c.grab() == ViewController::Grab::Object);
    r.feed(T::Release, p + glm::dvec2(40, 0));
    CHECK(r.scene.objects[0].position_m != default_scene().objects[0].position_m);
    CHECK(same_camera(r.c.camera, before));
}

TEST_CASE("terrain is never picked up by a plain drag, even when selected", "[ui][controller]") {
    // A 400 x 400 m slab under a sonar that reaches 5 m: terrain.
    SceneDesc s = default_scene();
    s.seafloor.reset();
    s.objects[0].box_m = Vec3d{400, 400, 2};
    s.objects[0].position_m = {0, 0, -1};
    Rig r;
    r.scene = s;
    SceneGeometry geometry(s);
    r.c.selected = 0;
    const glm::dvec2 p = r.pixel_of({1.5, 1.5, 0.0});
    InputEvent e;
    auto feed = [&](T t, glm::dvec2 at, int m = 0) {
        e.type = t, e.pos = at, e.button = button::Left, e.mods = m;
        if (auto next = r.c.handle(e, {r.scene, geometry, r.view, false})) {
            r.scene = *next;
            geometry.update_transforms(r.scene);
        }
    };
    const OrbitCamera before = r.c.camera;
    feed(T::Press, p);
    feed(T::Move, p + glm::dvec2(0, 30));
    CHECK(r.c.grab() == ViewController::Grab::Orbit);
    feed(T::Release, p + glm::dvec2(0, 30));
    CHECK(r.scene.objects[0].position_m == s.objects[0].position_m);
    CHECK_FALSE(same_camera(r.c.camera, before));
    CHECK(r.c.selected == 0);
    // With Shift held it moves (up and down): a deliberate edit.
    r.c.camera = before;
    feed(T::Press, p, mods::Shift);
    feed(T::Move, p + glm::dvec2(0, -30), mods::Shift);
    CHECK(r.c.grab() == ViewController::Grab::Object);
    feed(T::Release, p + glm::dvec2(0, -30), mods::Shift);
    CHECK(r.scene.objects[0].position_m[2] > s.objects[0].position_m[2] + 0.05);
}

// Offscreen drawing of the 3D view (GL side): a headless EGL context (Mesa surfaceless) and drawing into a
// framebuffer object of the current context. The GL-free entry points are in view3d.hpp.
#pragma once
#include "ui/model/camera.hpp"
#include "ui/gl/scene_renderer.hpp"
#include "ui/gl/view3d.hpp"

#include "core/display/image.hpp"
#include "core/data/scene.hpp"

#include <string>

namespace sonarsim::ui {

/// An OpenGL 3.3 core context without any display or window (EGL, Mesa surfaceless), current on this
/// thread while it lives. Throws std::runtime_error saying which step failed.
class HeadlessGLContext {
  public:
    HeadlessGLContext();
    ~HeadlessGLContext();
    HeadlessGLContext(const HeadlessGLContext&) = delete;
    HeadlessGLContext& operator=(const HeadlessGLContext&) = delete;

  private:
    void* display_ = nullptr;
    void* context_ = nullptr;
};

/// Draws the 3D view into a w x h framebuffer object of the current context and reads it back (RGB, top
/// row first). Leaves the default framebuffer bound.
Image8 render_view_image(SceneRenderer& renderer, const SceneDesc& scene, const OrbitCamera& camera, int w,
                         int h, const ViewOverlay& overlay);

} // namespace sonarsim::ui

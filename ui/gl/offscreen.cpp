#include "ui/gl/offscreen.hpp"

#include "ui/model/framing.hpp"
#include "ui/model/sonar_geometry.hpp"

#include "core/io/output.hpp"

#include <epoxy/egl.h>
#include <stdexcept>
#include <string>

namespace sonarsim::ui {
namespace {

[[noreturn]] void egl_fail(const char* step) {
    char code[16];
    std::snprintf(code, sizeof code, "0x%04X", unsigned(eglGetError()));
    throw std::runtime_error(std::string("headless OpenGL (EGL, Mesa surfaceless) failed at ") + step +
                             " (EGL error " + code + ")");
}

} // namespace

HeadlessGLContext::HeadlessGLContext() {
    EGLDisplay dpy = EGL_NO_DISPLAY;
    if (epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_MESA_platform_surfaceless") ||
        epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_platform_base"))
        dpy = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (dpy == EGL_NO_DISPLAY) egl_fail("eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA)");
    EGLint major = 0, minor = 0;
    if (!eglInitialize(dpy, &major, &minor)) egl_fail("eglInitialize");
    const EGLint config_attr[] = {EGL_SURFACE_TYPE,
                                  EGL_PBUFFER_BIT,
                                  EGL_RENDERABLE_TYPE,
                                  EGL_OPENGL_BIT,
                                  EGL_RED_SIZE,
                                  8,
                                  EGL_GREEN_SIZE,
                                  8,
                                  EGL_BLUE_SIZE,
                                  8,
                                  EGL_DEPTH_SIZE,
                                  24,
                                  EGL_NONE};
    EGLConfig config;
    EGLint n = 0;
    if (!eglChooseConfig(dpy, config_attr, &config, 1, &n) || n < 1) {
        eglTerminate(dpy);
        egl_fail("eglChooseConfig");
    }
    if (!eglBindAPI(EGL_OPENGL_API)) {
        eglTerminate(dpy);
        egl_fail("eglBindAPI(EGL_OPENGL_API)");
    }
    const EGLint ctx_attr[] = {EGL_CONTEXT_MAJOR_VERSION,
                               3,
                               EGL_CONTEXT_MINOR_VERSION,
                               3,
                               EGL_CONTEXT_OPENGL_PROFILE_MASK,
                               EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                               EGL_NONE};
    EGLContext ctx = eglCreateContext(dpy, config, EGL_NO_CONTEXT, ctx_attr);
    if (ctx == EGL_NO_CONTEXT) {
        eglTerminate(dpy);
        egl_fail("eglCreateContext (OpenGL 3.3 core)");
    }
    if (!eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
        eglDestroyContext(dpy, ctx);
        eglTerminate(dpy);
        egl_fail("eglMakeCurrent");
    }
    display_ = dpy, context_ = ctx;
}

HeadlessGLContext::~HeadlessGLContext() {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display_, context_);
    eglTerminate(display_);
}

Image8 render_view_image(SceneRenderer& renderer, const SceneDesc& scene, const OrbitCamera& camera, int w,
                         int h, const ViewOverlay& overlay) {
    gl::Framebuffer fbo(w, h);
    fbo.bind();
    renderer.draw(scene, camera, 0, 0, w, h, overlay);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    Image8 img = gl::read_pixels_rgb(0, 0, w, h);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return img;
}

std::vector<std::uint8_t> view3d_png_headless(const SceneDesc& scene, int w, int h) {
    const auto meshes = object_meshes(scene); // InputError for a bad mesh, before any GL
    HeadlessGLContext context;
    SceneRenderer renderer;
    renderer.set_meshes(meshes);
    return encode_png(render_view_image(renderer, scene,
                                        default_camera(scene, object_bounds(scene, meshes), double(w) / h), w,
                                        h, ViewOverlay{}));
}

void write_view3d_png(const SceneDesc& scene, const std::string& path, int w, int h) {
    write_files_atomically({{path, view3d_png_headless(scene, w, h)}});
}

} // namespace sonarsim::ui

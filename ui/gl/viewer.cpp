// The app loop: window, ImGui set-up, frame scheduling (idle waits, scripted frames, --orbit), drawing.
#include <epoxy/gl.h>
#include <GLFW/glfw3.h>

#include "ui/gl/viewer_app.hpp"

#include "core/base/timing.hpp"

#include "ui/model/display_mesh.hpp"
#include "ui/model/layout.hpp"
#include "ui/model/panel_layout.hpp"

#include <algorithm>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <chrono>
#include <cstdio>
#include <imgui.h>
#include <iostream>
#include <stdexcept>

namespace sonarsim::ui {
namespace {

void glfw_error(int code, const char* text) {
    std::cerr << "sonarsim: GLFW error " << code << ": " << text << "\n";
}

} // namespace

Viewer::Viewer(const ViewerOptions& o) : opt_(o), orbiter_(o.scene), session_(o.scene), undo_(o.scene) {
    // InputError before any window opens.
    script_ = ScriptPlayer(o.script.empty() ? std::vector<ScriptStep>{} : load_script(o.script), o.script,
                           o.mouse, o.drag, o.frames);
    glfwSetErrorCallback(glfw_error);
    if (!glfwInit())
        throw std::runtime_error("cannot start GLFW (no display? run under `xvfb-run -a`, or use "
                                 "`sonarsim render --view3d FILE.png` for a headless 3D view)");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    window_ = glfwCreateWindow(o.width, o.height, "sonarsim", nullptr, nullptr);
    if (!window_) {
        glfwTerminate();
        throw std::runtime_error("cannot open an OpenGL 3.3 window (no display? run under `xvfb-run -a`)");
    }
    update_title();
    glfwMakeContextCurrent(window_);
    const bool sync = o.frames > 0 || o.orbit || script_.has_script();
    glfwSwapInterval(sync ? 0 : 1);
    session_.set_notify([] { glfwPostEmptyEvent(); });
    float sx = 1, sy = 1;
    glfwGetWindowContentScale(window_, &sx, &sy);
    content_scale_ = std::max(1.0f, std::max(sx, sy));

    ui_.ui_scale = o.ui_scale;
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;
    // Software OpenGL (llvmpipe) spends a few ms per frame on the thin fringe triangles of anti-aliased
    // lines and fills; without them the panels look nearly the same.
    const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const std::string gl_renderer = renderer ? renderer : "";
    software_gl_ = gl_renderer.find("llvmpipe") != std::string::npos ||
                   gl_renderer.find("softpipe") != std::string::npos;
    ImGui_ImplGlfw_InitForOpenGL(window_, true);
    ImGui_ImplOpenGL3_Init("#version 330 core");
    input_ = std::make_unique<GlfwInput>(window_); // after ImGui's callbacks: ours run first

    renderer_ = std::make_unique<SceneRenderer>();
    sonar_ = std::make_unique<SonarPanel>();
    update_scale();
    layout_ = viewer_layout(o.width, o.height, font_scale_, fan_aspect(o.scene.sonar));
    reset_camera();
}

Viewer::~Viewer() {
    session_.set_notify({}); // the worker outlives the GLFW context: stop it from posting events
    renderer_.reset();
    sonar_.reset();
    input_.reset();
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    glfwDestroyWindow(window_);
    glfwTerminate();
}

void Viewer::update_scale() {
    const float want = content_scale_ * ui_.ui_scale;
    if (std::abs(want - font_scale_) < 1e-3f) return;
    font_scale_ = want;
    ImGuiIO& io = ImGui::GetIO();
    io.Fonts->Clear();
    ImFontConfig cfg;
    cfg.SizePixels = std::round(13.0f * want);
    io.Fonts->AddFontDefault(&cfg);
    ImGui_ImplOpenGL3_DestroyFontsTexture();
    ImGui_ImplOpenGL3_CreateFontsTexture();
    ImGuiStyle style;
    ImGui::StyleColorsDark(&style);
    style.WindowRounding = 0;
    if (software_gl_) style.AntiAliasedLines = style.AntiAliasedFill = false;
    style.ScaleAllSizes(want);
    ImGui::GetStyle() = style;
    // The font atlas is drawn 1:1 on pixel centres: nearest filtering looks the same and costs less under
    // software OpenGL than the backend's linear filtering.
    const GLuint font = GLuint(reinterpret_cast<std::uintptr_t>(io.Fonts->TexID));
    if (font != 0) {
        glBindTexture(GL_TEXTURE_2D, font);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
}

int Viewer::run() {
    for (int i = 0;
         !quit_ && !glfwWindowShouldClose(window_) && (script_.last_frame() < 0 || i <= script_.last_frame());
         ++i)
        frame(i);
    if (opt_.drag) {
        const Pose& p = session_.scene().sonar.pose;
        std::fprintf(stderr, "sonar pose after the drag: %.4f,%.4f,%.4f,%.3f,%.3f,%.3f\n", p.position_m[0],
                     p.position_m[1], p.position_m[2], p.orientation_deg[0], p.orientation_deg[1],
                     p.orientation_deg[2]);
    }
    if (opt_.orbit) {
        // The first frame includes start-up (first trace, shader compiles): leave it out.
        FrameStats& stats = pacer_.stats();
        stats.preview = opt_.orbit_preview;
        if (opt_.orbit_preview) { // then the last pose held: its full-quality image (the research tolerance)
            session_.submit(false);
            if (session_.wait_full(std::chrono::milliseconds(60000)) && session_.shown())
                stats.full_image_ms = session_.shown()->wall_ms;
        }
        std::printf("%s\n", stats.json_line(1).c_str());
        std::fflush(stdout);
    }
    return 0;
}

void Viewer::frame(int index) {
    const bool sync = script_.last_frame() >= 0 || opt_.orbit;
    if (pacer_.poll_now(sync || trajectory_.playing))
        glfwPollEvents();
    else // idle: sleep until input arrives or the worker posts a finished image
        glfwWaitEventsTimeout(1.0);
    pacer_.begin_frame();
    for (const InputEvent& e : script_.input(index, ui_.widgets.item_rects)) input_->inject(e);
    open_files(input_->take_dropped());

    if (opt_.orbit && opt_.orbit_pipelined) {
        // Pipelined: show the image of the previous frame's pose (waiting for it if needed), then request
        // this frame's pose so that the worker traces it while this frame is drawn.
        session_.wait_latest(std::chrono::milliseconds(20000));
        const Pose p = orbiter_.at(index);
        session_.edit([&](SceneDesc& s) { s.sonar.pose = p; });
        session_.submit(opt_.orbit_preview);
    } else if (sync) {
        if (opt_.orbit) {
            const Pose p = orbiter_.at(index);
            session_.edit([&](SceneDesc& s) { s.sonar.pose = p; });
        }
        // --orbit measures the full-quality retrace per frame (or, with --orbit-preview, a drag's preview);
        // scripted frames render as the interactive viewer does.
        session_.submit(opt_.orbit ? opt_.orbit_preview : interacting_);
        session_.wait_latest(std::chrono::milliseconds(20000));
    } else {
        session_.poll();
    }
    if (snapshots_.pending() > 0) session_.wait_full(std::chrono::milliseconds(60000));
    // A named snapshot after this frame (--snapshot, a script's snapshot step) reads its annotated PNG from
    // this frame: an image whose rays were kept from an earlier shading is first replaced by the one placed
    // anew, which the files will hold.
    const bool last = script_.last_frame() >= 0 && index >= script_.last_frame();
    if (((last && !opt_.snapshot.empty()) || script_.has_action(index, "snapshot")) && session_.place_anew())
        session_.wait_latest(std::chrono::milliseconds(60000));
    if (session_.shown())
        pacer_.count_image(session_.shown_count(), *session_.shown(), index > 0 || !opt_.orbit);

    int fb_w = 0, fb_h = 0, win_w = 0, win_h = 0;
    glfwGetFramebufferSize(window_, &fb_w, &fb_h);
    glfwGetWindowSize(window_, &win_w, &win_h);
    // The window may have moved to a monitor of another content scale. Where the framebuffer is already
    // larger than the window (macOS), that part of the scale is done by the framebuffer.
    float csx = 1, csy = 1;
    glfwGetWindowContentScale(window_, &csx, &csy);
    const float fb_ratio = win_w > 0 ? std::max(1.0f, float(fb_w) / float(win_w)) : 1.0f;
    content_scale_ = std::max(1.0f, std::max(csx, csy) / fb_ratio);
    update_scale();
    layout_ = viewer_layout(win_w, win_h, font_scale_, fan_aspect(session_.scene().sonar));

    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    input_->feed_imgui();
    ImGui::NewFrame();
    menu_bar();
    ui_.frame_ms = pacer_.last_frame_ms();
    draw_controls_panel(layout_.controls, session_, ui_, trajectory_);
    sonar_->draw(layout_.sonar, session_, controller_.surface_hover(), font_scale_);
    dialogs();
    help_window();
    handle_events();
    draw_view_text(layout_.view3d);
    interacting_ = controller_.editing_scene() || ImGui::IsAnyItemActive();
    record_undo();
    if (session_.scene().sampling.bounces > 0) last_bounces_ = session_.scene().sampling.bounces;
    if (auto p = trajectory_.update(session_.scene().sonar.pose, pacer_.last_frame_ms() / 1000.0))
        session_.edit([&](SceneDesc& s) { s.sonar.pose = *p; });
    // While the sonar is on the trajectory (played, paused, at its end), a side-scan's or scan's pings are
    // heard along it: the waterfall scrolls.
    const bool on_track = !trajectory_.recording && trajectory_.track.size() >= 2 &&
                          trajectory_.track.passes(session_.scene().sonar.pose, trajectory_.t_s);
    session_.set_ping_track(on_track ? trajectory_.track.shared() : nullptr, trajectory_.t_s);
    if (!sync && session_.submit(interacting_) != 0) pacer_.keep_drawing();
    // Keep drawing while a drag is held, and until the full-quality image of a preview has been requested
    // (the input rests for Session::kRest).
    if (controller_.pressed() || session_.full_pending()) pacer_.keep_drawing();

    if (ui_.want_snapshot) snapshots_.ask(), ui_.want_snapshot = false;
    const bool full_on_screen = session_.shown() && !session_.shown()->preview();

    upload_meshes();
    draw_gl(fb_w, fb_h, win_w, win_h);
    take_pending_snapshots(full_on_screen, fb_w, fb_h, win_w, win_h);
    script_actions(index, fb_w, fb_h);
    if (last && !opt_.screenshot.empty()) write_screenshot(opt_.screenshot, fb_w, fb_h);
    if (last && !opt_.layout.empty()) write_layout(opt_.layout, win_w, win_h);
    if (last && !opt_.state.empty()) write_state(opt_.state);
    if (last && !opt_.snapshot.empty()) {
        take_snapshot(opt_.snapshot, false, annotated_now(fb_w, fb_h, win_w, win_h));
        if (!session_.error().empty()) throw std::runtime_error(session_.error());
    }
    glfwSwapBuffers(window_);
    pacer_.end_frame();
}

void Viewer::upload_meshes() {
    if (meshes_uploaded_ == session_.meshes_version()) return;
    // Once per geometry change. Software OpenGL takes a few hundred thousand triangles per frame, not
    // millions: above kDisplayTriangles the view draws vertex-clustered copies (tracing keeps the full
    // meshes).
    const std::vector<std::shared_ptr<const TriMesh>> meshes = session_.local_meshes();
    size_t triangles = 0;
    for (const auto& m : meshes) triangles += m->triangles.size();
    if (triangles > kDisplayTriangles) {
        const auto t0 = std::chrono::steady_clock::now();
        const auto simple = simplify_for_display(meshes, kDisplayTriangles);
        const double ms = ms_since(t0);
        size_t drawn = 0;
        for (const auto& m : simple) drawn += m->triangles.size();
        renderer_->set_meshes(simple);
        std::fprintf(stderr, "3D view: %zu triangles drawn as %zu (simplified in %.0f ms)\n", triangles,
                     drawn, ms);
    } else {
        renderer_->set_meshes(meshes);
    }
    meshes_uploaded_ = session_.meshes_version();
}

void Viewer::draw_gl(int fb_w, int fb_h, int win_w, int win_h) {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, fb_w, fb_h);
    // The panels draw no background of their own: a clear is far cheaper than ImGui's textured quads
    // under software OpenGL.
    const ImVec4 bg = ImGui::GetStyle().Colors[ImGuiCol_WindowBg];
    glClearColor(bg.x, bg.y, bg.z, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    const float sx = win_w > 0 ? float(fb_w) / win_w : 1, sy = win_h > 0 ? float(fb_h) / win_h : 1;
    const Rect& v = layout_.view3d;
    renderer_->draw(session_.scene(), controller_.camera, int(v.x * sx), int((win_h - v.y - v.h) * sy),
                    int(v.w * sx), int(v.h * sy), overlay());
    ImGui::Render();
    glViewport(0, 0, fb_w, fb_h);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

int run_viewer(const ViewerOptions& options) {
    ViewerOptions o = options;
    if ((!o.screenshot.empty() || !o.snapshot.empty() || !o.layout.empty() || !o.state.empty()) &&
        o.frames <= 0 && o.script.empty())
        o.frames = 3;
    Viewer v(o);
    return v.run();
}

} // namespace sonarsim::ui

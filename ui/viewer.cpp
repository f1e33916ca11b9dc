#include <epoxy/gl.h>
#include <GLFW/glfw3.h>

#include "viewer.hpp"

#include "controls_panel.hpp"
#include "display_mesh.hpp"
#include "file_dialog.hpp"
#include "interaction.hpp"
#include "layout.hpp"
#include "offscreen.hpp"
#include "orbit.hpp"
#include "scene_renderer.hpp"
#include "session.hpp"
#include "snapshot.hpp"
#include "sonar_geometry.hpp"
#include "sonar_panel.hpp"

#include "core/output.hpp"
#include "core/pose.hpp"

#include <algorithm>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <imgui.h>
#include <iostream>
#include <memory>
#include <stdexcept>

namespace sonarsim::ui {
namespace {

using Clock = std::chrono::steady_clock;

double ms_between(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
}

std::string lower_ext(const std::string& path) {
    const size_t dot = path.find_last_of('.');
    std::string e = dot == std::string::npos ? "" : path.substr(dot);
    for (auto& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
    return e;
}

const std::vector<std::string> kMeshExt = {".obj", ".ply", ".stl", ".off"};

class Viewer {
  public:
    explicit Viewer(const ViewerOptions& o);
    ~Viewer();
    int run();

  private:
    void frame(int index);
    void menu_bar();
    void dialogs();
    void view3d_input(const Rect& view);
    void shortcuts();
    void take_snapshot(const Rect& view, const std::string& prefix);
    void reset_camera();
    ViewOverlay overlay() const;
    void draw_view_text(const Rect& view);

    ViewerOptions opt_;
    Orbiter orbiter_;
    GLFWwindow* window_ = nullptr;
    Session session_;
    std::unique_ptr<SceneRenderer> renderer_;
    std::unique_ptr<SonarPanel> sonar_;
    ControlsUi ui_;
    OrbitCamera camera_;
    FileDialog open_dialog_, mesh_dialog_, save_dialog_;
    std::vector<std::string> dropped_;
    std::uint64_t meshes_uploaded_ = 0;

    // 3D interaction.
    enum class CameraDrag { None, Orbit, Pan } camera_drag_ = CameraDrag::None;
    std::optional<FrustumDrag> frustum_drag_;
    bool sonar_hot_ = false;
    std::optional<glm::dvec3> surface_hover_;
    glm::dvec2 press_px_{0};
    /// A drag that edits the scene is held (the frustum, or a slider): its changes render as previews.
    bool interacting_ = false;

    // Timing.
    FrameStats stats_;
    double last_frame_ms_ = 0;
    std::uint64_t counted_images_ = 0;
    bool quit_ = false;
    int extra_frames_ = 0;
};

void glfw_error(int code, const char* text) {
    std::cerr << "sonarsim: GLFW error " << code << ": " << text << "\n";
}

void on_drop(GLFWwindow* w, int count, const char** paths) {
    auto* list = static_cast<std::vector<std::string>*>(glfwGetWindowUserPointer(w));
    for (int i = 0; i < count; ++i) list->push_back(paths[i]);
}

Viewer::Viewer(const ViewerOptions& o) : opt_(o), orbiter_(o.scene), session_(o.scene) {
    glfwSetErrorCallback(glfw_error);
    if (!glfwInit())
        throw std::runtime_error("cannot start GLFW (no display? run under `xvfb-run -a`, or use "
                                 "`sonarsim render --view3d FILE.png` for a headless 3D view)");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    const std::string title =
        "sonarsim - " + (o.scene.source_file.empty() ? std::string("Fig. 9 scene") : o.scene.source_file);
    window_ = glfwCreateWindow(o.width, o.height, title.c_str(), nullptr, nullptr);
    if (!window_) {
        glfwTerminate();
        throw std::runtime_error("cannot open an OpenGL 3.3 window (no display? run under `xvfb-run -a`)");
    }
    glfwMakeContextCurrent(window_);
    glfwSwapInterval(o.frames > 0 || o.orbit ? 0 : 1);
    glfwSetWindowUserPointer(window_, &dropped_);
    glfwSetDropCallback(window_, on_drop);
    session_.set_notify([] { glfwPostEmptyEvent(); });

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;
    ImGui::StyleColorsDark();
    ImGui::GetStyle().WindowRounding = 0;
    // Software OpenGL (llvmpipe) spends a few ms per frame on the thin fringe triangles of anti-aliased
    // lines and fills; without them the panels look nearly the same.
    const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const std::string gl_renderer = renderer ? renderer : "";
    if (gl_renderer.find("llvmpipe") != std::string::npos ||
        gl_renderer.find("softpipe") != std::string::npos)
        ImGui::GetStyle().AntiAliasedLines = ImGui::GetStyle().AntiAliasedFill = false;
    ImGui_ImplGlfw_InitForOpenGL(window_, true);
    ImGui_ImplOpenGL3_Init("#version 330 core");

    renderer_ = std::make_unique<SceneRenderer>();
    sonar_ = std::make_unique<SonarPanel>();
    const ViewerLayout L = viewer_layout(o.width, o.height);
    camera_ = default_camera(o.scene, double(L.view3d.w) / L.view3d.h);
}

Viewer::~Viewer() {
    session_.set_notify({}); // the worker outlives the GLFW context: stop it from posting events
    renderer_.reset();
    sonar_.reset();
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    glfwDestroyWindow(window_);
    glfwTerminate();
}

int Viewer::run() {
    for (int i = 0; !quit_ && !glfwWindowShouldClose(window_) && (opt_.frames <= 0 || i < opt_.frames); ++i)
        frame(i);
    if (opt_.drag) {
        const Pose& p = session_.scene().sonar.pose;
        std::fprintf(stderr, "sonar pose after the drag: %.4f,%.4f,%.4f,%.3f,%.3f,%.3f\n", p.position_m[0],
                     p.position_m[1], p.position_m[2], p.orientation_deg[0], p.orientation_deg[1],
                     p.orientation_deg[2]);
    }
    if (opt_.orbit) {
        // The first frame includes start-up (first trace, shader compiles): leave it out.
        stats_.preview = opt_.orbit_preview;
        std::printf("%s\n", stats_.json_line(1).c_str());
        std::fflush(stdout);
    }
    return 0;
}

void Viewer::frame(int index) {
    const bool sync = opt_.frames > 0 || opt_.orbit;
    if (sync || extra_frames_ > 0) {
        glfwPollEvents();
        extra_frames_ = std::max(0, extra_frames_ - 1);
    } else {
        // Idle: sleep until input arrives or the worker posts a finished image, then draw a few frames so
        // that ImGui settles (hover states, animations).
        glfwWaitEventsTimeout(1.0);
        extra_frames_ = 2;
    }
    const Clock::time_point t0 = Clock::now();

    for (const std::string& path : dropped_) {
        const std::string e = lower_ext(path);
        if (e == ".json")
            session_.open_scene(path);
        else if (std::find(kMeshExt.begin(), kMeshExt.end(), e) != kMeshExt.end())
            session_.add_mesh(path);
        else
            session_.set_error(path + ": not a scene (.json) or mesh (.obj .ply .stl .off)");
    }
    dropped_.clear();

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
        // scripted frames (--frames, --drag) render as the interactive viewer does.
        session_.submit(opt_.orbit ? opt_.orbit_preview : interacting_);
        session_.wait_latest(std::chrono::milliseconds(20000));
    } else {
        session_.poll();
    }
    if (session_.shown() && session_.shown_count() != counted_images_) {
        counted_images_ = session_.shown_count();
        if (index > 0 || !opt_.orbit) stats_.image_ms.push_back(session_.shown()->wall_ms);
    }

    int fb_w = 0, fb_h = 0, win_w = 0, win_h = 0;
    glfwGetFramebufferSize(window_, &fb_w, &fb_h);
    glfwGetWindowSize(window_, &win_w, &win_h);
    const ViewerLayout L = viewer_layout(win_w, win_h);

    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    if (index == 0) {
        // The font atlas is drawn 1:1 on pixel centres: nearest filtering looks the same and costs less
        // under software OpenGL than the backend's linear filtering.
        const GLuint font = GLuint(reinterpret_cast<std::uintptr_t>(ImGui::GetIO().Fonts->TexID));
        if (font != 0) {
            glBindTexture(GL_TEXTURE_2D, font);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        }
    }
    if (opt_.mouse) ImGui::GetIO().MousePos = ImVec2(float(opt_.mouse->x), float(opt_.mouse->y));
    if (opt_.drag && opt_.frames >= 4) {
        // Frame 0: hover at the start; 1: press; then move linearly; last frame: release at the end.
        const double t = std::clamp(double(index - 1) / (opt_.frames - 3), 0.0, 1.0);
        const glm::dvec2 p = (*opt_.drag)[0] + t * ((*opt_.drag)[1] - (*opt_.drag)[0]);
        ImGuiIO& io = ImGui::GetIO();
        io.MousePos = ImVec2(float(p.x), float(p.y));
        io.MouseDown[0] = index >= 1 && index < opt_.frames - 1;
    }
    ImGui::NewFrame();
    menu_bar();
    ui_.frame_ms = last_frame_ms_;
    draw_controls_panel(L.controls, session_, ui_);
    sonar_->draw(L.sonar, session_, surface_hover_);
    dialogs();
    view3d_input(L.view3d);
    shortcuts();
    draw_view_text(L.view3d);
    interacting_ = frustum_drag_.has_value() || ImGui::IsAnyItemActive();
    if (!sync && session_.submit(interacting_) != 0) extra_frames_ = 2;
    // Keep drawing while a drag is held, and until the full-quality image of a preview has been requested
    // (the input rests for Session::kRest).
    if (frustum_drag_ || camera_drag_ != CameraDrag::None || session_.full_pending()) extra_frames_ = 2;

    if (meshes_uploaded_ != session_.meshes_version()) {
        // Once per geometry change. Software OpenGL takes a few hundred thousand triangles per frame, not
        // millions: above kDisplayTriangles the view draws vertex-clustered copies (tracing keeps the full
        // meshes).
        const std::vector<std::shared_ptr<const TriMesh>> meshes = session_.local_meshes();
        size_t triangles = 0;
        for (const auto& m : meshes) triangles += m->triangles.size();
        if (triangles > kDisplayTriangles) {
            const Clock::time_point t0 = Clock::now();
            const auto simple = simplify_for_display(meshes, kDisplayTriangles);
            const double ms = ms_between(t0, Clock::now());
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
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, fb_w, fb_h);
    // The panels draw no background of their own: a clear is far cheaper than ImGui's textured quads
    // under software OpenGL.
    const ImVec4 bg = ImGui::GetStyle().Colors[ImGuiCol_WindowBg];
    glClearColor(bg.x, bg.y, bg.z, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    const float sx = win_w > 0 ? float(fb_w) / win_w : 1, sy = win_h > 0 ? float(fb_h) / win_h : 1;
    const Rect& v = L.view3d;
    renderer_->draw(session_.scene(), camera_, int(v.x * sx), int((win_h - v.y - v.h) * sy), int(v.w * sx),
                    int(v.h * sy), overlay());
    ImGui::Render();
    glViewport(0, 0, fb_w, fb_h);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());

    const bool last = opt_.frames > 0 && index + 1 >= opt_.frames;
    if (last && !opt_.screenshot.empty()) {
        glReadBuffer(GL_BACK);
        write_files_atomically({{opt_.screenshot, encode_png(gl::read_pixels_rgb(0, 0, fb_w, fb_h))}});
        std::cerr << "wrote " << opt_.screenshot << " (" << fb_w << "x" << fb_h << ")\n";
    }
    if (ui_.want_snapshot || (last && !opt_.snapshot.empty())) {
        ui_.want_snapshot = false;
        take_snapshot(L.view3d, last ? opt_.snapshot : "");
        if (last && !opt_.snapshot.empty() && !session_.error().empty())
            throw std::runtime_error(session_.error());
    }
    glfwSwapBuffers(window_);
    last_frame_ms_ = ms_between(t0, Clock::now());
    stats_.frame_ms.push_back(last_frame_ms_);
}

void Viewer::menu_bar() {
    if (!ImGui::BeginMainMenuBar()) return;
    if (ImGui::BeginMenu("File")) {
        if (ImGui::MenuItem("Open scene...", "O")) ui_.want_open = true;
        if (ImGui::MenuItem("Add mesh...")) ui_.want_add_mesh = true;
        if (ImGui::MenuItem("Save scene as...")) ui_.want_save = true;
        ImGui::Separator();
        if (ImGui::MenuItem("Snapshot", "S")) ui_.want_snapshot = true;
        ImGui::Separator();
        if (ImGui::MenuItem("Quit", "Ctrl+Q")) quit_ = true;
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("View")) {
        ImGui::MenuItem("Raw polar image", "P", &sonar_->polar);
        ImGui::MenuItem("Show traced hits", "H", &ui_.show_hits);
        if (ImGui::MenuItem("Reset camera", "F")) ui_.want_reset_camera = true;
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Help")) {
        ImGui::TextUnformatted("3D view: left-drag orbit, right/middle-drag pan, wheel zoom.\n"
                               "Drag the sonar frustum: move it on the floor plane;\n"
                               "  Shift: up/down, Ctrl: yaw (x) and pitch (y), Ctrl+Shift or Alt: roll.\n"
                               "Click an object: select it for the material editor.\n"
                               "Sonar image: hover a pixel to see its elevation arc (yellow) and the\n"
                               "  surface points that echo into it (magenta); hover a surface in 3D to\n"
                               "  see its pixel (red).\n"
                               "Keys: S snapshot, P raw polar, H traced hits, F reset camera, O open.\n"
                               "Drop a scene (.json) or mesh (.obj .ply .stl .off) on the window.");
        ImGui::EndMenu();
    }
    ImGui::EndMainMenuBar();
}

void Viewer::dialogs() {
    const std::string dir = session_.scene().source_file.empty()
                                ? "."
                                : std::filesystem::path(session_.scene().source_file).parent_path().string();
    if (ui_.want_open) open_dialog_.open("Open scene", false, {".json"}, dir), ui_.want_open = false;
    if (ui_.want_add_mesh) mesh_dialog_.open("Add mesh", false, kMeshExt, dir), ui_.want_add_mesh = false;
    if (ui_.want_save) save_dialog_.open("Save scene", true, {".json"}, dir), ui_.want_save = false;
    if (ui_.want_reset_camera) reset_camera(), ui_.want_reset_camera = false;
    std::string path;
    if (open_dialog_.draw(path) && session_.open_scene(path)) reset_camera();
    if (mesh_dialog_.draw(path)) session_.add_mesh(path);
    if (save_dialog_.draw(path)) session_.save_scene(path);
}

void Viewer::view3d_input(const Rect& view) {
    const ImGuiIO& io = ImGui::GetIO();
    const glm::dvec2 m(io.MousePos.x, io.MousePos.y);
    const bool inside = view.contains(m.x, m.y) && !io.WantCaptureMouse;
    const int w = int(view.w), h = int(view.h);
    const Ray ray = camera_.ray_through(m.x - view.x, m.y - view.y, w, h);
    const SceneDesc& scene = session_.scene();

    // Press: grab the frustum, or start moving the camera.
    if (inside && io.MouseClicked[0]) {
        press_px_ = m;
        if (auto t = pick_sonar(ray, scene.sonar)) {
            DragMode mode = DragMode::Translate;
            if ((io.KeyCtrl && io.KeyShift) || io.KeyAlt)
                mode = DragMode::Roll;
            else if (io.KeyCtrl)
                mode = DragMode::YawPitch;
            else if (io.KeyShift)
                mode = DragMode::Vertical;
            frustum_drag_ = begin_drag(mode, scene.sonar.pose, ray, *t, m);
        } else {
            camera_drag_ = CameraDrag::Orbit;
        }
    }
    if (inside && (io.MouseClicked[1] || io.MouseClicked[2])) camera_drag_ = CameraDrag::Pan;

    if (frustum_drag_) {
        if (io.MouseDown[0]) {
            const Pose p = drag_pose(*frustum_drag_, ray, m);
            session_.edit([&](SceneDesc& s) { s.sonar.pose = p; });
        } else {
            frustum_drag_.reset();
        }
    } else if (camera_drag_ == CameraDrag::Orbit) {
        if (io.MouseDown[0]) {
            camera_.orbit(io.MouseDelta.x, io.MouseDelta.y);
        } else {
            camera_drag_ = CameraDrag::None;
            // A click without motion selects the object under the mouse.
            if (glm::length(m - press_px_) < 3)
                if (auto hit = pick_surface(ray, session_.geometry(), scene.seafloor))
                    ui_.selected = int(hit->material) - 1;
        }
    } else if (camera_drag_ == CameraDrag::Pan) {
        if (io.MouseDown[1] || io.MouseDown[2])
            camera_.pan(io.MouseDelta.x, io.MouseDelta.y, h);
        else
            camera_drag_ = CameraDrag::None;
    }
    if (inside && io.MouseWheel != 0) camera_.zoom(io.MouseWheel);

    // Hover: highlight the frustum, and find the surface point under the mouse.
    sonar_hot_ = frustum_drag_.has_value();
    surface_hover_.reset();
    if (inside && camera_drag_ == CameraDrag::None && !frustum_drag_) {
        sonar_hot_ = pick_sonar(ray, scene.sonar).has_value();
        if (auto hit = pick_surface(ray, session_.geometry(), scene.seafloor)) surface_hover_ = hit->point;
    }
}

void Viewer::shortcuts() {
    const ImGuiIO& io = ImGui::GetIO();
    if (io.WantCaptureKeyboard || open_dialog_.is_open() || mesh_dialog_.is_open() || save_dialog_.is_open())
        return;
    if (io.KeyCtrl) {
        if (ImGui::IsKeyPressed(GLFW_KEY_Q, false)) quit_ = true;
        return;
    }
    if (ImGui::IsKeyPressed(GLFW_KEY_S, false)) ui_.want_snapshot = true;
    if (ImGui::IsKeyPressed(GLFW_KEY_P, false)) sonar_->polar = !sonar_->polar;
    if (ImGui::IsKeyPressed(GLFW_KEY_H, false)) ui_.show_hits = !ui_.show_hits;
    if (ImGui::IsKeyPressed(GLFW_KEY_F, false)) ui_.want_reset_camera = true;
    if (ImGui::IsKeyPressed(GLFW_KEY_O, false)) ui_.want_open = true;
}

ViewOverlay Viewer::overlay() const {
    ViewOverlay ov;
    ov.sonar_hot = sonar_hot_;
    ov.selected_object = ui_.selected;
    ov.marker = surface_hover_;
    const RenderResult* shown = session_.shown();
    if (shown && sonar_->hovered()) {
        const ImagePlace& p = *sonar_->hovered();
        ov.arc = elevation_arc(shown->scene.sonar, p.range_m, p.azimuth_deg);
        ov.echo_points = echoing_points(shown->frame->hits(), shown->scene, p.bin, p.beam);
    }
    if (shown && ui_.show_hits)
        for (auto& beam : shown->frame->hits().cells)
            for (auto& c : beam) ov.hit_points.push_back(c.point);
    return ov;
}

void Viewer::draw_view_text(const Rect& v) {
    ImDrawList* dl = ImGui::GetBackgroundDrawList();
    char buf[256];
    const RenderResult* shown = session_.shown();
    if (shown)
        std::snprintf(buf, sizeof buf, "frame %.1f ms   image %.1f ms%s", last_frame_ms_, shown->wall_ms,
                      shown->frame->preview() ? " (preview)" : "");
    else
        std::snprintf(buf, sizeof buf, "frame %.1f ms   image: rendering...", last_frame_ms_);
    dl->AddText(ImVec2(v.x + 8, v.y + 6), IM_COL32(230, 235, 240, 255), buf);
    const Pose& p = session_.scene().sonar.pose;
    std::snprintf(buf, sizeof buf, "sonar (%.2f, %.2f, %.2f) m  rpy (%.1f, %.1f, %.1f) deg", p.position_m[0],
                  p.position_m[1], p.position_m[2], p.orientation_deg[0], p.orientation_deg[1],
                  p.orientation_deg[2]);
    dl->AddText(ImVec2(v.x + 8, v.y + 22), IM_COL32(170, 220, 255, 255), buf);
    dl->AddText(ImVec2(v.x + 8, v.y + v.h - 50), IM_COL32(200, 200, 200, 200),
                "drag the frustum: move it on the floor plane");
    dl->AddText(ImVec2(v.x + 8, v.y + v.h - 34), IM_COL32(200, 200, 200, 200),
                "  Shift: up/down  Ctrl: yaw/pitch  Ctrl+Shift: roll");
    dl->AddText(ImVec2(v.x + 8, v.y + v.h - 18), IM_COL32(200, 200, 200, 200),
                "left-drag: orbit  right-drag: pan  wheel: zoom");
}

void Viewer::reset_camera() {
    int w = 0, h = 0;
    glfwGetWindowSize(window_, &w, &h);
    const Rect v = viewer_layout(w, h).view3d;
    camera_ = default_camera(session_.scene(), double(v.w) / std::max(1.0f, v.h));
}

void Viewer::take_snapshot(const Rect& view, const std::string& prefix) {
    // A snapshot is of the full-quality image of the edited scene, never of a drag's preview.
    session_.wait_full(std::chrono::milliseconds(60000));
    const RenderResult* shown = session_.shown();
    if (!shown) {
        session_.set_error("no sonar image yet: nothing to snapshot");
        return;
    }
    Bytes png;
    try {
        const auto meshes = object_meshes(shown->scene);
        SceneRenderer r;
        r.set_meshes(meshes);
        png = encode_png(render_view_image(r, shown->scene, camera_, std::max(16, int(view.w)),
                                           std::max(16, int(view.h)), overlay()));
    } catch (const std::exception& e) {
        session_.set_error(std::string("3D view snapshot failed: ") + e.what());
    }
    if (session_.snapshot(prefix.empty() ? default_snapshot_prefix(ui_.snapshot_dir) : prefix, png))
        std::cerr << session_.status() << "\n";
}

} // namespace

int run_viewer(const ViewerOptions& options) {
    ViewerOptions o = options;
    if ((!o.screenshot.empty() || !o.snapshot.empty()) && o.frames <= 0) o.frames = 3;
    Viewer v(o);
    return v.run();
}

} // namespace sonarsim::ui

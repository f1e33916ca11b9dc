// What the viewer draws besides the panels: the 3D overlays and text, the window title; snapshots.
#include <epoxy/gl.h>
#include <GLFW/glfw3.h>

#include "ui/gl/viewer_app.hpp"

#include "ui/gl/gl_util.hpp"
#include "ui/gl/offscreen.hpp"
#include "ui/model/framing.hpp"
#include "ui/model/panel_layout.hpp"
#include "ui/model/snapshot.hpp"
#include "ui/model/sonar_geometry.hpp"

#include "core/io/output.hpp"

#include <cstdio>
#include <filesystem>
#include <imgui.h>
#include <iostream>

namespace sonarsim::ui {

ViewOverlay Viewer::overlay() const {
    ViewOverlay ov;
    ov.sonar_hot = controller_.sonar_hot();
    ov.selected_object = ui_.selected;
    ov.marker = controller_.surface_hover();
    ov.handles = frustum_handles(session_.scene());
    const RenderResult* shown = session_.shown();
    const bool along = session_.on_ping_track() && shown && shown->pings &&
                       shown->scene.sonar.kind == session_.scene().sonar.kind;
    ov.fields = fields_of_view(session_.scene(), along ? &shown->pings->schedule : nullptr);
    if (shown && shown->frame && sonar_->hovered()) {
        const ImagePlace& p = *sonar_->hovered();
        ov.arc = elevation_arc(shown->scene.sonar, p.range_m, p.azimuth_deg);
        ov.echo_points = echoing_points(shown->frame->hits(), shown->scene, p.bin, p.beam);
        const EchoPath& path = sonar_->hovered_path().path(); // of the shown frame and its scene
        for (const auto& q : path.points_m) ov.echo_path.emplace_back(q[0], q[1], q[2]);
        ov.echo_path_scatterer = size_t(1 + path.out_bounces);
    }
    if (shown && shown->frame && ui_.show_hits)
        for (auto& beam : shown->frame->hits().cells)
            for (auto& c : beam) ov.hit_points.push_back(c.point_m);
    return ov;
}

void Viewer::draw_view_text(const Rect& v) {
    // Lines that do not fit the view's width are left out rather than run into the sonar panel.
    ImDrawList* dl = ImGui::GetBackgroundDrawList();
    const float line = ImGui::GetTextLineHeightWithSpacing(), pad = 0.5f * line;
    // Each line on a dark translucent backdrop, so that it reads over sand, terrain or open water alike.
    auto put = [&](float y, ImU32 col, const char* text) {
        const ImVec2 sz = ImGui::CalcTextSize(text);
        if (sz.x > v.w - 2 * pad || y < v.y || y + line > v.y + v.h) return;
        const float m = 0.25f * pad;
        dl->AddRectFilled(ImVec2(v.x + pad - 2 * m, y - m), ImVec2(v.x + pad + sz.x + 2 * m, y + line - m),
                          IM_COL32(8, 12, 18, 170), 2 * m);
        dl->AddText(ImVec2(v.x + pad, y), col, text);
    };
    char buf[256];
    const RenderResult* shown = session_.shown();
    if (shown)
        std::snprintf(buf, sizeof buf, "frame %.1f ms   image %.1f ms%s", pacer_.last_frame_ms(),
                      shown->wall_ms, shown->preview() ? " (preview)" : "");
    else
        std::snprintf(buf, sizeof buf, "frame %.1f ms   image: rendering...", pacer_.last_frame_ms());
    put(v.y + pad * 0.5f, IM_COL32(230, 235, 240, 255), buf);
    const Pose& p = session_.scene().sonar.pose;
    std::snprintf(buf, sizeof buf, "sonar (%.2f, %.2f, %.2f) m  rpy (%.1f, %.1f, %.1f) deg", p.position_m[0],
                  p.position_m[1], p.position_m[2], p.orientation_deg[0], p.orientation_deg[1],
                  p.orientation_deg[2]);
    put(v.y + pad * 0.5f + line, IM_COL32(170, 220, 255, 255), buf);
    if (trajectory_.recording || trajectory_.playing) {
        std::snprintf(buf, sizeof buf, "%s trajectory: %zu poses", trajectory_.recording ? "REC" : "PLAY",
                      trajectory_.track.size());
        put(v.y + pad * 0.5f + 2 * line, IM_COL32(255, 90, 90, 255), buf);
    }
    const char* hints[] = {"drag the sonar (housing or handle): move it",
                           "  Shift: up/down  Ctrl: yaw/pitch  Ctrl+Shift: roll  Alt: fine",
                           "click an object to select it, then drag it",
                           "  Shift: up/down  Ctrl: turn  Alt: scale",
                           "left-drag: orbit  right: pan  wheel: zoom  F: frame"};
    float y = v.y + v.h - pad * 0.5f - 5 * line;
    for (const char* h : hints) put(y, IM_COL32(200, 200, 200, 200), h), y += line;
}

void Viewer::reset_camera() {
    int w = 0, h = 0;
    glfwGetWindowSize(window_, &w, &h);
    const Rect v = viewer_layout(w, h, font_scale_, fan_aspect(session_.scene().sonar)).view3d;
    controller_.camera =
        default_camera(session_.scene(), object_bounds(session_.scene(), session_.local_meshes()),
                       double(v.w) / std::max(1.0f, v.h));
}

void Viewer::update_title() {
    const std::string& f = session_.scene().source_file;
    const std::string name =
        f.empty() ? std::string("Fig. 9 scene") : std::filesystem::path(f).filename().string();
    if (name == title_file_) return;
    title_file_ = name;
    glfwSetWindowTitle(window_, ("sonarsim - " + name).c_str());
}

void Viewer::take_snapshot(const std::string& prefix_in, bool as_shown, const Bytes& annotated) {
    // A snapshot is of a full-quality image, never of a drag's preview: of the edited scene, or (`as_shown`)
    // of the image on screen with the scene it was made from. `annotated`: the sonar panel as drawn this
    // frame (empty: no annotated PNG, never an older frame's, whose hover marker would be stale).
    if (!session_.shown() || session_.shown()->preview() || (!as_shown && session_.busy()))
        session_.wait_full(std::chrono::milliseconds(60000));
    const RenderResult* shown = session_.shown();
    if (!shown) {
        session_.set_error("no sonar image yet: nothing to snapshot");
        return;
    }
    const Rect& view = layout_.view3d;
    Bytes png;
    try {
        const auto meshes = object_meshes(shown->scene);
        SceneRenderer r;
        r.set_meshes(meshes);
        png = encode_png(render_view_image(r, shown->scene, controller_.camera, std::max(16, int(view.w)),
                                           std::max(16, int(view.h)), overlay()));
    } catch (const std::exception& e) {
        session_.set_error(std::string("3D view snapshot failed: ") + e.what());
    }
    const std::string prefix = prefix_in.empty() ? default_snapshot_prefix(ui_.snapshot_dir) : prefix_in;
    if (!session_.snapshot(prefix, png, ui_.annotated_snapshot ? annotated : Bytes{})) return;
    snapshots_.written();
    std::cerr << session_.status() << "\n";
}

Bytes Viewer::annotated_now(int fb_w, int fb_h, int win_w, int win_h) const {
    // The sonar panel's image, labels and colour bar exactly as drawn this frame, when that frame shows the
    // full-quality image of the scene being edited, as `render` places its rays (else the snapshot's images
    // would not match it).
    const RenderResult* shown = session_.shown();
    if (!ui_.annotated_snapshot || win_w <= 0 || win_h <= 0 || !shown || shown->preview() ||
        session_.busy() || session_.shown_kept_placement())
        return {};
    const float sx = float(fb_w) / win_w, sy = float(fb_h) / win_h;
    const Rect r = sonar_->annotated_rect();
    const int x0 = std::max(0, int(r.x * sx)), x1 = std::min(fb_w, int((r.x + r.w) * sx));
    const int y0 = std::max(0, int((win_h - r.y - r.h) * sy)), y1 = std::min(fb_h, int((win_h - r.y) * sy));
    if (x1 <= x0 || y1 <= y0) return {};
    glReadBuffer(GL_BACK);
    return encode_png(gl::read_pixels_rgb(x0, y0, x1 - x0, y1 - y0));
}

void Viewer::take_pending_snapshots(bool full_on_screen, int fb_w, int fb_h, int win_w, int win_h) {
    if (snapshots_.pending() == 0) return;
    // With a preview drawn, the next frame waits for the full image first; with an image whose rays were
    // kept from an earlier shading, for the one placed anew that the files will hold, so that the
    // annotated PNG read back from the screen shows it.
    if (full_on_screen && session_.place_anew()) full_on_screen = false;
    const Bytes annotated = full_on_screen ? annotated_now(fb_w, fb_h, win_w, win_h) : Bytes{};
    if (!snapshots_.serve(full_on_screen, [&] { take_snapshot("", true, annotated); })) pacer_.keep_drawing();
}

} // namespace sonarsim::ui

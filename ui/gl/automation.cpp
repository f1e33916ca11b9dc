// Automation: the --script actions after a frame is drawn (its input goes through the GLFW callbacks:
// ScriptPlayer), screenshots, and the state and text-layout exports the tests check.
#include <epoxy/gl.h>
#include <GLFW/glfw3.h>

#include "ui/gl/viewer_app.hpp"

#include "ui/gl/controls_panel.hpp"
#include "ui/gl/gl_util.hpp"
#include "ui/model/sonar_geometry.hpp"
#include "ui/model/text_layout.hpp"

#include "core/base/errors.hpp"
#include "core/io/output.hpp"
#include "core/scene/params.hpp"
#include "core/data/pose.hpp"
#include "core/scene/scene_io.hpp"

#include <algorithm>
#include <imgui.h>
#include <imgui_internal.h>
#include <iostream>

namespace sonarsim::ui {

void Viewer::script_actions(int index, int fb_w, int fb_h) {
    int win_w = 0, win_h = 0;
    glfwGetWindowSize(window_, &win_w, &win_h);
    for (const ScriptStep& st : script_.actions(index)) {
        const std::string& c = st.command;
        if (c == "screenshot") write_screenshot(st.args[0], fb_w, fb_h);
        if (c == "state") write_state(st.args[0]);
        if (c == "layout") write_layout(st.args[0], win_w, win_h);
        if (c == "snapshot") take_snapshot(st.args[0], false, annotated_now(fb_w, fb_h, win_w, win_h));
        if (c == "quit") quit_ = true;
        if (c == "ground_truth") session_.set_ground_truth(st.args[0] == "on");
        if (c == "open") open_files({st.args[0]});
        if (c == "trajectory_save") save_trajectory(trajectory_.track, st.args[0]);
        if (c == "trajectory_load") {
            trajectory_.track = load_trajectory(st.args[0]);
            trajectory_.t_s = 0;
            if (!trajectory_.track.empty())
                session_.edit([&](SceneDesc& s) { s.sonar.pose = trajectory_.track.samples().front().pose; });
        }
        if (c == "trajectory_snapshots") trajectory_snapshots(st.args[0]);
    }
}

void Viewer::trajectory_snapshots(const std::string& prefix) {
    // Playback of the trajectory, one snapshot per pose: PREFIX.<k> (the images `render --pose` gives).
    const auto& samples = trajectory_.track.samples();
    for (size_t k = 0; k < samples.size(); ++k) {
        session_.edit([&](SceneDesc& s) { s.sonar.pose = samples[k].pose; });
        take_snapshot(prefix + "." + std::to_string(k));
    }
}

void Viewer::write_screenshot(const std::string& path, int fb_w, int fb_h) const {
    glReadBuffer(GL_BACK);
    write_files_atomically({{path, encode_png(gl::read_pixels_rgb(0, 0, fb_w, fb_h))}});
    std::cerr << "wrote " << path << " (" << fb_w << "x" << fb_h << ")\n";
}

void Viewer::write_state(const std::string& path) const {
    const SceneDesc& s = session_.scene();
    const OrbitCamera& c = controller_.camera;
    json objects = json::array();
    for (const ObjectDesc& o : s.objects)
        objects.push_back(
            {{"position", o.position_m}, {"orientation_deg", o.orientation_deg}, {"scale", o.scale}});
    // Where things are on screen (window px), for scripts and xdotool sessions.
    const Rect& v = layout_.view3d;
    auto on_screen = [&](const glm::dvec3& w) {
        glm::dvec2 px;
        if (!c.project(w, int(v.w), int(v.h), px)) return json(nullptr);
        return json::array({px.x + v.x, px.y + v.y});
    };
    glm::dvec3 body(0);
    const TriMesh housing = sonar_body(s.sonar);
    for (const auto& p : housing.vertices) body += glm::dvec3(p) / double(housing.vertices.size());
    json handles = json::array(), centres = json::array();
    for (const glm::dvec3& h : frustum_handles(s)) handles.push_back(on_screen(h));
    for (const ObjectDesc& o : s.objects) centres.push_back(on_screen(to_glm(o.position_m)));
    json hover = nullptr; // the hovered image cell and its strongest echo path
    if (const HoveredPath& hp = sonar_->hovered_path(); hp.valid())
        hover = {{"bin", hp.bin()},
                 {"beam", hp.beam()},
                 {"path_points", hp.path().points_m.size()},
                 {"bounces", hp.path().bounces},
                 {"object_id", hp.path().object_id}};
    const json j = {
        {"screen",
         {{"housing", on_screen(body)},
          {"handles", handles},
          {"objects", centres},
          {"view3d", {v.x, v.y, v.w, v.h}}}},
        {"camera",
         {{"target", {c.target.x, c.target.y, c.target.z}},
          {"distance_m", c.distance_m},
          {"azimuth_deg", c.azimuth_deg},
          {"elevation_deg", c.elevation_deg}}},
        {"pose", {{"position", s.sonar.pose.position_m}, {"orientation_deg", s.sonar.pose.orientation_deg}}},
        {"objects", objects},
        {"selected", ui_.selected},
        {"scene", scene_to_json(s)},
        {"measurement", sonar_->measurement()},
        {"hover", hover},
        {"snapshots", snapshots_.written_count()},
        {"image_placement_kept", session_.shown_kept_placement()},
        {"popups_open", ImGui::GetCurrentContext()->OpenPopupStack.Size},
        {"help_open", show_help_},
        {"undo_steps", undo_.undo_steps()},
        {"redo_steps", undo_.redo_steps()},
        {"trajectory_poses", trajectory_.track.size()},
        {"scene_file", s.source_file},
        {"window_title", "sonarsim - " + title_file_},
        {"error", session_.error()},
        {"status", session_.status()}};
    write_files_atomically({{path, to_bytes(j.dump(2) + "\n")}});
}

void Viewer::write_layout(const std::string& path, int win_w, int win_h) const {
    // Every glyph drawn this frame, from ImGui's draw data: a triangle textured away from the atlas's white
    // pixel is part of a glyph (anti-aliased lines do not use the atlas: AntiAliasedLinesUseTex is off).
    const ImDrawData* dd = ImGui::GetDrawData();
    const ImVec2 white = ImGui::GetIO().Fonts->TexUvWhitePixel;
    std::vector<Glyph> glyphs;
    std::vector<std::string> names;
    for (int l = 0; dd && l < dd->CmdListsCount; ++l) {
        const ImDrawList* list = dd->CmdLists[l];
        names.push_back(list->_OwnerName ? list->_OwnerName : "?");
        for (const ImDrawCmd& cmd : list->CmdBuffer) {
            if (cmd.UserCallback || cmd.TextureId != ImGui::GetIO().Fonts->TexID) continue; // images
            const Rect clip{cmd.ClipRect.x, cmd.ClipRect.y, cmd.ClipRect.z - cmd.ClipRect.x,
                            cmd.ClipRect.w - cmd.ClipRect.y};
            Rect last{-1, -1, -1, -1};
            for (unsigned k = 0; k + 2 < cmd.ElemCount; k += 3) {
                const ImDrawVert* v[3];
                bool textured = false;
                for (int i = 0; i < 3; ++i) {
                    v[i] = &list->VtxBuffer[int(cmd.VtxOffset +
                                                list->IdxBuffer[int(cmd.IdxOffset + k + unsigned(i))])];
                    textured |=
                        std::abs(v[i]->uv.x - white.x) > 1e-6f || std::abs(v[i]->uv.y - white.y) > 1e-6f;
                }
                if (!textured) continue;
                float x0 = v[0]->pos.x, x1 = x0, y0 = v[0]->pos.y, y1 = y0;
                for (int i = 1; i < 3; ++i)
                    x0 = std::min(x0, v[i]->pos.x), x1 = std::max(x1, v[i]->pos.x),
                    y0 = std::min(y0, v[i]->pos.y), y1 = std::max(y1, v[i]->pos.y);
                const Rect box{x0, y0, x1 - x0, y1 - y0};
                if (box.x == last.x && box.y == last.y && box.w == last.w && box.h == last.h) continue;
                last = box;
                glyphs.push_back({box, clip, l});
            }
        }
    }
    std::vector<TextRun> runs = text_runs(glyphs);
    json out_runs = json::array();
    for (TextRun& r : runs) {
        r.list_name = names[size_t(r.list)];
        out_runs.push_back({{"x", r.box.x},
                            {"y", r.box.y},
                            {"w", r.box.w},
                            {"h", r.box.h},
                            {"window", r.list_name},
                            {"cut_x", r.cut_x},
                            {"glyphs", r.glyphs}});
    }
    // Text must also keep off the sonar image (the fan itself, or the raw polar image) and the colour bar.
    std::vector<KeepOut> keep_out;
    json out_keep = json::array();
    if (sonar_->has_layout()) {
        const SonarPanelLayout& P = sonar_->layout();
        keep_out.push_back({"sonar image", P.image, sonar_->polar ? std::nullopt : std::optional(P.fan)});
        keep_out.push_back({"colour bar", P.colorbar, std::nullopt});
        for (const KeepOut& k : keep_out)
            out_keep.push_back(
                {{"name", k.name}, {"x", k.rect.x}, {"y", k.rect.y}, {"w", k.rect.w}, {"h", k.rect.h}});
    }
    const std::string problems = layout_problems(runs, float(win_w), float(win_h), keep_out);
    const json j = {{"width", win_w},
                    {"height", win_h},
                    {"runs", out_runs},
                    {"keep_out", out_keep},
                    {"problems", problems}};
    write_files_atomically({{path, to_bytes(j.dump(1) + "\n")}});
    std::cerr << "wrote " << path << ": " << runs.size() << " text runs"
              << (problems.empty() ? ", no overlaps\n" : ", problems:\n" + problems);
}

} // namespace sonarsim::ui

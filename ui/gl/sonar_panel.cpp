// The sonar image panel: header (view, colour map), the fan or raw polar image with its labels, hover and
// 3D-marker feedback. Plots and measurement are in sonar_plots.cpp.
#include "ui/gl/sonar_panel.hpp"

#include "core/display/display_range.hpp"

#include "ui/model/image_views.hpp"
#include "core/data/pose.hpp"
#include "core/display/polar_layout.hpp"
#include "ui/gl/sonar_panel_style.hpp"
#include "ui/model/measure.hpp"

#include "core/scene/params.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <imgui.h>
#include <limits>

namespace sonarsim::ui {
using namespace panel;

void SonarPanel::draw_header(const Session& session, Session& edit) {
    if (session.scene().sonar.kind == SonarKind::Imaging) { // a waterfall or a sweep has one view
        int view = polar ? 1 : 0;
        ImGui::RadioButton("fan", &view, 0);
        ImGui::SameLine();
        ImGui::RadioButton("raw polar (P)", &view, 1);
        polar = view == 1;
    }
    // The colour maps of core's parameter table.
    const std::string now = find_param("display.colormap")->get(session.scene()).get<std::string>();
    const float room = ImGui::GetContentRegionAvail().x - ImGui::GetCursorPosX();
    if (room > 9 * ImGui::GetFontSize()) ImGui::SameLine();
    ImGui::SetNextItemWidth(7 * ImGui::GetFontSize());
    if (ImGui::BeginCombo("##cmap", now.c_str())) {
        for (const std::string& c : find_param("display.colormap")->choices)
            if (ImGui::Selectable(c.c_str(), c == now)) edit.set("display.colormap", c);
        ImGui::EndCombo();
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("colour map (display.colormap)");
}

void SonarPanel::draw_pings(const Rect& area, const RenderResult& shown, std::uint64_t shown_count) {
    has_layout_ = false; // no fan: its layout, hover and measuring do not apply
    if (uploaded_count_ != shown_count) {
        texture_.upload(*shown.ping_image);
        uploaded_count_ = shown_count, uploaded_polar_ = false;
    }
    const PingSeries& p = *shown.pings;
    const SceneDesc& sc = shown.scene;
    const bool side = p.kind == SonarKind::Sidescan;
    char what[200], facts[200];
    if (side) {
        std::snprintf(what, sizeof what, "waterfall, %s range: port | starboard, newest at the top",
                      sc.sidescan.range == SidescanRange::Ground ? "ground" : "slant");
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (double h : p.first_return_m)
            if (std::isfinite(h)) lo = std::min(lo, h), hi = std::max(hi, h);
        if (std::isfinite(lo))
            std::snprintf(facts, sizeof facts, "%d pings %.1f ms apart, altitude %.2f-%.2f m", p.pings,
                          1e3 * p.ping_interval_s, lo, hi);
        else
            std::snprintf(facts, sizeof facts, "%d pings, %.1f ms apart; no bottom return", p.pings,
                          1e3 * p.ping_interval_s);
    } else {
        std::snprintf(what, sizeof what, "sweep: forward up, port left, %.4g m to the edge",
                      sc.sonar.range_max_m);
        std::snprintf(facts, sizeof facts, "%d steps of %.3g deg, %.2f s a sweep", p.pings,
                      sc.scanning.step_deg, p.pings * p.ping_interval_s);
    }
    ImGui::TextUnformatted(what);
    ImGui::TextDisabled("%s", facts);
    const ImVec2 at = ImGui::GetCursorScreenPos();
    const float room_w = area.x + area.w - at.x - 4, room_h = area.y + area.h - at.y - 4;
    const Image8& img = *shown.ping_image;
    if (room_w < 8 || room_h < 8 || img.width < 1 || img.height < 1) return;
    // Fitted without distortion for a sweep (its geometry is the picture); a waterfall takes the room (its
    // rows are pings, not metres).
    float w = room_w, h = room_h;
    if (!side) {
        const float k = std::min(room_w / float(img.width), room_h / float(img.height));
        w = k * float(img.width), h = k * float(img.height);
    }
    const ImVec2 top(at.x + 0.5f * (room_w - w), at.y);
    ImGui::SetCursorScreenPos(top);
    ImGui::Image(reinterpret_cast<ImTextureID>(static_cast<std::uintptr_t>(texture_.id())), ImVec2(w, h));
    annotated_ = {top.x, top.y, w, h};
    if (!side && !p.schedule.empty()) { // the head's newest step: forward up, port (a positive angle) left
        const double a = deg2rad(p.schedule.back().head_deg);
        const ImVec2 c(top.x + 0.5f * w, top.y + 0.5f * h);
        const float r = 0.5f * w;
        ImGui::GetWindowDrawList()->AddLine(
            c, ImVec2(c.x - r * float(std::sin(a)), c.y - r * float(std::cos(a))),
            IM_COL32(90, 220, 255, 230), std::max(1.5f, 0.12f * ImGui::GetFontSize()));
    }
    if (shown.preview())
        text_at(ImGui::GetWindowDrawList(), ImVec2(top.x + w, top.y + h), IM_COL32(255, 200, 80, 255),
                "preview (base grid only)", 1.0f, 1.0f);
}

void SonarPanel::ask_fan_height(const Rect& area, Session& session, float scale) {
    // The fan formed as high as it is shown (in device pixels), not one row per range bin: a 512-beam fan is
    // 3721 x 2048 px in full. Asked from the layout of the full fan, so that the fan's own layout (its width
    // rounds up at each height) cannot feed back. The next image comes at this height.
    // Laid out again only when what the layout reads changed (the grid stands for the fan's geometry).
    if (polar) return;
    const SceneDesc& sc = session.scene();
    FanHeightAsked now{area,
                       scale,
                       ImGui::GetIO().DisplayFramebufferScale.y,
                       {ImGui::CalcTextSize("0").x, ImGui::GetTextLineHeight()},
                       sonar_grid(sc.sonar),
                       sc.display.lo_db,
                       sc.display.hi_db,
                       colorbar_title(sc)};
    if (!asked_ || !asked_->same_as(now)) {
        const SonarPanelLayout L =
            sonar_panel_layout(area, {sc.sonar, now.lo_db, now.hi_db, now.title, false}, now.text, scale);
        now.height_px = fan_height_to_form(double(L.image.h) * now.framebuffer_scale, *now.grid);
        asked_ = std::move(now);
    }
    session.set_fan_height_px(asked_->height_px);
}

bool SonarPanel::FanHeightAsked::same_as(const FanHeightAsked& o) const {
    return area.x == o.area.x && area.y == o.area.y && area.w == o.area.w && area.h == o.area.h &&
           scale == o.scale && framebuffer_scale == o.framebuffer_scale && text.char_w == o.text.char_w &&
           text.line_h == o.text.line_h && grid == o.grid && lo_db == o.lo_db && hi_db == o.hi_db &&
           title == o.title;
}

void SonarPanel::draw(const Rect& area, Session& session, const std::optional<glm::dvec3>& marker,
                      float scale) {
    hovered_.reset();
    path_.clear();
    scale_ = scale;
    ImGui::SetNextWindowPos(ImVec2(area.x, area.y));
    ImGui::SetNextWindowSize(ImVec2(area.w, area.h));
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                                   ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoTitleBar |
                                   ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse |
                                   ImGuiWindowFlags_NoBringToFrontOnFocus | ImGuiWindowFlags_NoBackground;
    ImGui::Begin("Sonar image", nullptr, flags);
    const RenderResult* shown = session.shown();
    draw_header(session, session);

    if (!shown) {
        ImGui::TextDisabled("rendering the first image...");
        ask_fan_height(area, session, scale); // the first image at the height it will be shown
        ImGui::End();
        return;
    }
    if (shown->pings) {
        draw_pings(area, *shown, session.shown_count());
        ImGui::End();
        return;
    }
    const Frame& f = *shown->frame;
    const SonarParams& s = shown->scene.sonar;
    if (uploaded_count_ != session.shown_count() || uploaded_polar_ != polar) {
        texture_.upload(polar ? polar_color_image(f.polar(), f.display)
                              : fan_with_no_echo(f, shown->scene.display.colormap));
        uploaded_count_ = session.shown_count(), uploaded_polar_ = polar;
    }
    // The layout of the fan as formed (its pixel width is rounded up at its own height).
    PanelContent content{s,
                         f.display.lo_db,
                         f.display.hi_db,
                         colorbar_title(shown->scene),
                         polar,
                         polar ? 0 : f.sector().height};
    layout_ =
        sonar_panel_layout(area, content, {ImGui::CalcTextSize("0").x, ImGui::GetTextLineHeight()}, scale);
    has_layout_ = true;
    const SonarPanelLayout& L = layout_;
    ask_fan_height(area, session, scale);
    { // What an annotated snapshot holds: the image, its labels, the colour bar with its ticks and title.
        Rect a = L.image;
        auto add = [&](const Rect& r) {
            const float x0 = std::min(a.x, r.x), y0 = std::min(a.y, r.y);
            a = {x0, y0, std::max(a.x + a.w, r.x + r.w) - x0, std::max(a.y + a.h, r.y + r.h) - y0};
        };
        for (const auto* list : {&L.bearings, &L.ranges, &L.colorbar_ticks})
            for (const PanelLabel& l : *list) add(l.box);
        add(L.colorbar), add(L.colorbar_title.box);
        const float m = 4 * scale;
        annotated_ = {a.x - m, a.y - m, a.w + 2 * m, a.h + 2 * m};
    }
    ImDrawList* dl = ImGui::GetWindowDrawList();
    ImGui::SetCursorScreenPos(ImVec2(L.image.x, L.image.y));
    ImGui::Image(reinterpret_cast<ImTextureID>(static_cast<std::uintptr_t>(texture_.id())),
                 ImVec2(L.image.w, L.image.h));
    if (f.preview()) // a drag's image: the full-quality one follows when the input rests
        text_at(dl, ImVec2(L.readout.x + L.readout.w, L.readout.y + L.readout.h), IM_COL32(255, 200, 80, 255),
                f.placement_stale  ? "preview (re-shaded, no ray traced)"
                : !f.hits().halves ? "preview (base grid only)"
                : f.error_estimate.valid && f.error_estimate.median_abs_db <= half_grey_level_db(f.display)
                    ? "preview (the screen's precision)"
                    : "preview (coarser than the screen)",
                1.0f, 1.0f);

    // Hover: the place under the mouse.
    const ImVec2 mouse = ImGui::GetIO().MousePos;
    if (ImGui::IsWindowHovered() && L.image.contains(mouse.x, mouse.y)) {
        hovered_ = place_at(L.image, *shown, mouse);
        if (measuring_ && hovered_) {
            if (ImGui::IsMouseClicked(0))
                measure_a_ = measure_b_ = hovered_;
            else if (ImGui::IsMouseDown(0) && measure_a_)
                measure_b_ = hovered_;
        }
        if (hovered_) {
            ascan_beam_ = hovered_->beam, ascan_beams_ = s.beams;
            ascan_azimuth_deg_ = hovered_->azimuth_deg;
        }
    }
    if (hovered_)
        path_.update(*shown, session.shown_count(), hovered_->bin, hovered_->beam);
    else
        path_.clear();
    if (polar)
        draw_polar_overlay(L.image, *shown);
    else
        draw_fan_overlay(L.image, *shown);

    // The pixel of the hovered 3D surface point.
    if (measuring_ && !last_measure_.empty()) {
        ImGui::SetCursorScreenPos(ImVec2(area.x + 8 * scale, L.readout.y));
        ImGui::PushTextWrapPos(area.w - 8 * scale); // window-local
        ImGui::TextColored(ImVec4(0.3f, 1, 0.65f, 1), "%s", last_measure_.c_str());
        ImGui::PopTextWrapPos();
    } else if (marker) {
        const SectorLayout SL(f.grid_ptr, f.sector().height);
        const PointInImage p = locate_world_point(s, SL, *marker);
        ImVec2 q;
        if (polar) {
            const PolarLayout PL(f.grid());
            q = ImVec2(L.image.x + float(PL.u_of_azimuth_deg(p.azimuth_deg)) * L.image.w,
                       L.image.y + float(PL.v_of_range_m(p.range_m)) * L.image.h);
        } else {
            q = ImVec2(L.image.x + float(p.px / f.sector().width) * L.image.w,
                       L.image.y + float(p.py / f.sector().height) * L.image.h);
        }
        if (L.image.contains(q.x, q.y)) {
            const ImU32 c = p.in_view ? kMarkerColor : IM_COL32(160, 160, 160, 200);
            dl->AddCircle(q, 7, c, 16, 2);
            dl->AddLine(ImVec2(q.x - 11, q.y), ImVec2(q.x - 4, q.y), c, 2);
            dl->AddLine(ImVec2(q.x + 4, q.y), ImVec2(q.x + 11, q.y), c, 2);
        }
        char buf[160];
        std::snprintf(buf, sizeof buf, "3D point: r %.2f m  az %+.1f  el %+.1f deg%s", p.range_m,
                      p.azimuth_deg, p.elevation_deg,
                      p.in_view                                     ? ""
                      : !f.grid().in_elevation_deg(p.elevation_deg) ? " (el out of beam)"
                                                                    : " (out of view)");
        ImGui::SetCursorScreenPos(ImVec2(area.x + 8 * scale, L.readout.y));
        ImGui::PushTextWrapPos(area.w - 8 * scale); // window-local
        ImGui::TextColored(ImVec4(1, 0.5f, 0.5f, 1), "%s", buf);
        ImGui::PopTextWrapPos();
    } else if (hovered_) {
        const float level = f.polar().at(hovered_->bin, hovered_->beam);
        char lvl[32], buf[160];
        if (std::isfinite(level))
            std::snprintf(lvl, sizeof lvl, "%.1f dB", double(level));
        else
            std::snprintf(lvl, sizeof lvl, "no echo");
        std::snprintf(buf, sizeof buf, "r %.3f m  az %+.2f deg  bin %d beam %d: %s", hovered_->range_m,
                      hovered_->azimuth_deg, hovered_->bin, hovered_->beam, lvl);
        std::string text = buf;
        const std::string path = echo_path_text(path_.path()); // drawn in 3D
        if (!path.empty()) text += "\n" + path;
        if (const GroundTruth* gt = shown->ground_truth.get()) { // File > Ground truth: two lines
            const size_t at = size_t(hovered_->bin) * size_t(gt->beams) + size_t(hovered_->beam);
            if (gt->object_id[at] != -1) {
                std::snprintf(buf, sizeof buf, "\nbehind it: %s, el %+.2f deg (%+.2f ... %+.2f)",
                              echo_source_name(gt->object_id[at]).c_str(), gt->elevation_deg[at],
                              gt->elevation_min_deg[at], gt->elevation_max_deg[at]);
                text += buf;
                std::snprintf(buf, sizeof buf, "\n  incidence %.1f deg, %d surface%s", gt->incidence_deg[at],
                              gt->surfaces[at], gt->surfaces[at] == 1 ? "" : "s");
                text += buf;
            }
        }
        ImGui::SetCursorScreenPos(ImVec2(area.x + 8 * scale, L.readout.y));
        ImGui::PushTextWrapPos(area.w - 8 * scale); // window-local
        ImGui::TextColored(ImVec4(1, 0.9f, 0.3f, 1), "%s", text.c_str());
        ImGui::PopTextWrapPos();
    } else {
        ImGui::SetCursorScreenPos(ImVec2(area.x + 8 * scale, L.readout.y));
        ImGui::PushTextWrapPos(area.w - 8 * scale); // window-local
        ImGui::TextDisabled(measuring_ ? "measuring: drag on the image (Esc ends)"
                                       : "hover the image: its elevation arc shows in 3D");
        ImGui::PopTextWrapPos();
    }
    draw_measure(L.image, *shown);
    draw_labels();
    draw_colorbar(f.display); // the range shown (display.auto: from the image)
    draw_ascan(L.ascan, *shown);
    ImGui::End();
}

void SonarPanel::draw_fan_overlay(const Rect& r, const RenderResult& shown) {
    const SonarParams& s = shown.scene.sonar;
    const Frame& f = *shown.frame;
    const SectorLayout L(f.grid_ptr, f.sector().height);
    const SonarGrid& grid = f.grid();
    ImDrawList* dl = ImGui::GetWindowDrawList();
    auto to_screen = [&](double range, double az) {
        double px, py;
        L.polar_to_pixel(range, az, px, py);
        return ImVec2(r.x + float(px / f.sector().width) * r.w, r.y + float(py / f.sector().height) * r.h);
    };
    // Range rings from the fan's port edge to its starboard edge (a beam table's need not be symmetric) and
    // bearing lines, at the labelled values (labels: draw_labels, outside the fan).
    const double port = layout_.fan.port_deg, starboard = layout_.fan.starboard_deg;
    for (double rr : layout_.range_m) {
        const int n = 40;
        ImVec2 pts[n + 1];
        for (int k = 0; k <= n; ++k) pts[k] = to_screen(rr, port - (port - starboard) * k / n);
        dl->AddPolyline(pts, n + 1, kGridColor, 0, 1.0f);
    }
    for (double a : layout_.bearing_deg)
        dl->AddLine(to_screen(s.range_min_m, a), to_screen(s.range_max_m, a), kGridColor, 1.0f);
    if (hovered_) {
        // The hovered cell's outline: its range bin x beam.
        const double dr = grid.bin_m, r0 = grid.bin_near_edge_m(hovered_->bin);
        const double a0 = grid.column_azimuth_deg(hovered_->beam),
                     a1 = grid.column_azimuth_deg(hovered_->beam + 1);
        const double da = a0 - a1;
        const ImVec2 q[4] = {to_screen(r0, a0), to_screen(r0, a0 - da), to_screen(r0 + dr, a0 - da),
                             to_screen(r0 + dr, a0)};
        dl->AddPolyline(q, 4, kHoverColor, ImDrawFlags_Closed, 1.5f);
        dl->AddCircle(to_screen(hovered_->range_m, hovered_->azimuth_deg), 6, kHoverColor, 12, 1.5f);
    }
}

void SonarPanel::draw_labels() {
    ImDrawList* dl = ImGui::GetWindowDrawList();
    for (const auto* list : {&layout_.bearings, &layout_.ranges})
        for (const PanelLabel& l : *list) dl->AddText(ImVec2(l.box.x, l.box.y), kLabelColor, l.text.c_str());
}

void SonarPanel::draw_polar_overlay(const Rect& r, const RenderResult& shown) {
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const SonarGrid& grid = shown.frame->grid();
    const PolarLayout PL(grid);
    auto y_of = [&](double range) { return r.y + float(PL.v_of_range_m(range)) * r.h; };
    auto x_of = [&](double az) { return r.x + float(PL.u_of_azimuth_deg(az)) * r.w; };
    for (double rr : layout_.range_m)
        dl->AddLine(ImVec2(r.x, y_of(rr)), ImVec2(r.x + r.w, y_of(rr)), kGridColor);
    for (double a : layout_.bearing_deg)
        dl->AddLine(ImVec2(x_of(a), r.y), ImVec2(x_of(a), r.y + r.h), kGridColor);
    if (hovered_) {
        const double r0 = grid.bin_near_edge_m(hovered_->bin), r1 = grid.bin_near_edge_m(hovered_->bin + 1);
        const double a0 = grid.column_azimuth_deg(hovered_->beam),
                     a1 = grid.column_azimuth_deg(hovered_->beam + 1);
        dl->AddRect(ImVec2(x_of(a0) - 1, y_of(r1) - 1), ImVec2(x_of(a1) + 1, y_of(r0) + 1), kHoverColor);
    }
}

} // namespace sonarsim::ui

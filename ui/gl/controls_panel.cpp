#include "ui/gl/controls_panel.hpp"
#include "ui/gl/readout.hpp"

#include "core/scene/devices.hpp"
#include "core/scene/params.hpp"

#include "ui/model/bindings.hpp"
#include "ui/model/interaction.hpp"
#include "ui/model/scene_labels.hpp"

#include "core/meshfile/mesh_formats.hpp"

#include <imgui.h>
#include <imgui_internal.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <filesystem>
#include <cmath>

namespace sonarsim::ui {
namespace {

void help_tooltip(const ValueSpec& spec) {
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("%s\n%s: %s\nShift+drag: fine; Ctrl+click: type a value", spec.help.c_str(),
                          spec.key.c_str(), allowed_text(spec).c_str());
}

/// Shift held while a slider is dragged: the value moves kFineDrag as far per pixel, from where it was
/// when Shift went down.
bool fine_drag(ControlsWidgets& w, const SliderRange& r, double current, double& value) {
    const ImGuiIO& io = ImGui::GetIO();
    const ImGuiID id = ImGui::GetItemID();
    if (!ImGui::IsItemActive() || !io.KeyShift) {
        if (w.fine_id == id) w.fine_id = 0;
        return false;
    }
    if (w.fine_id != id) w.fine_id = id, w.fine_base = current, w.fine_mouse_x0 = io.MousePos.x;
    const float width = std::max(1.0f, ImGui::GetItemRectSize().x);
    const double t = double(io.MousePos.x - w.fine_mouse_x0) / width * kFineDrag;
    if (r.logarithmic && r.lo > 0)
        value = w.fine_base * std::pow(r.hi / r.lo, t);
    else
        value = w.fine_base + t * (r.hi - r.lo);
    value = std::clamp(value, r.lo, r.hi);
    return value != current;
}

/// SameLine() when a button labelled `next` still fits on this line.
void same_line_if_fits(const char* next) {
    const ImGuiStyle& st = ImGui::GetStyle();
    const float w = ImGui::CalcTextSize(next).x + 2 * st.FramePadding.x;
    const float right = ImGui::GetItemRectMax().x + st.ItemSpacing.x + w;
    if (right <= ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x) ImGui::SameLine();
}

void remember_rect(ControlsWidgets& w, const std::string& key) {
    // The part of the widget on screen: scrolled out of the sections, or under the footer, it is not
    // there to be clicked.
    const ImRect clip = ImGui::GetCurrentWindow()->ClipRect;
    const ImVec2 a = ImMax(ImGui::GetItemRectMin(), clip.Min), b = ImMin(ImGui::GetItemRectMax(), clip.Max);
    if (b.x > a.x && b.y > a.y) w.item_rects[key] = {a.x, a.y, b.x - a.x, b.y - a.y};
}

/// The label of a field: beside it (returned as the widget label) or drawn above it now.
std::string field_label(const ControlsWidgets& w, const std::string& text, const std::string& key) {
    if (!w.labels_above) return text + "##" + key;
    ImGui::TextUnformatted(text.c_str());
    ImGui::SetNextItemWidth(-1);
    return "##" + key;
}

float widest_label() {
    float w = 0;
    for (const ParamSpec& p : scene_params())
        if (p.type != ParamType::Vec3) w = std::max(w, ImGui::CalcTextSize(p.label_text().c_str()).x);
    for (const MaterialSpec& m : material_params())
        w = std::max(w, ImGui::CalcTextSize(m.label_text().c_str()).x);
    return w + ImGui::GetStyle().ItemInnerSpacing.x + 2;
}

/// One slider for a number or integer spec. Returns true with `value` set when edited.
bool slider(ControlsWidgets& w, const ValueSpec& spec, double current, double& value) {
    const SliderRange r = spec.slider_range();
    const std::string label = field_label(w, spec.label_text(), spec.key);
    ImGuiSliderFlags flags = r.logarithmic ? ImGuiSliderFlags_Logarithmic : 0;
    bool changed = false;
    if (spec.type == ParamType::Integer) {
        int v = int(current), lo = int(r.lo), hi = int(r.hi);
        changed = ImGui::SliderScalar(label.c_str(), ImGuiDataType_S32, &v, &lo, &hi, "%d", flags);
        value = v;
        if (fine_drag(w, r, current, value))
            value = std::round(value), changed = value != current;
        else if (w.fine_id == ImGui::GetItemID())
            changed = false;
    } else {
        double v = current;
        const double span = r.hi - r.lo;
        const char* fmt = span >= 500 ? "%.0f" : span >= 20 ? "%.1f" : "%.3g";
        changed = ImGui::SliderScalar(label.c_str(), ImGuiDataType_Double, &v, &r.lo, &r.hi, fmt,
                                      flags | ImGuiSliderFlags_NoRoundToFormat);
        value = v;
        if (fine_drag(w, r, current, value)) changed = true;
    }
    remember_rect(w, spec.key);
    help_tooltip(spec);
    return changed;
}

/// The value an optional parameter takes when switched on: the water surface half a metre above the
/// sonar.
double optional_default(const SceneDesc& s, const ParamSpec& p) {
    if (p.key == "water.surface_height_m") return s.sonar.pose.position_m[2] + 0.5;
    return std::max(p.min, 0.0);
}

/// A Vec3 row as three dragged numbers under its label; bounds from the row's slider range. Returns true
/// with `v` set when edited.
bool drag3(const ValueSpec& spec, Vec3d& v) {
    const SliderRange r = spec.slider_range();
    const bool degrees = spec.unit == "deg";
    ImGui::TextUnformatted(spec.label_text().c_str());
    ImGui::SetNextItemWidth(-1);
    const bool changed = ImGui::DragScalarN(("##" + spec.key).c_str(), ImGuiDataType_Double, v.data(), 3,
                                            degrees ? 0.2f : 0.005f, &r.lo, &r.hi, degrees ? "%.2f" : "%.3f");
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("%s\n%s: %s\nDrag, or Ctrl+click to type a value", spec.help.c_str(),
                          spec.key.c_str(), allowed_text(spec).c_str());
    return changed;
}

void section_params(ControlsWidgets& w, Session& session, Section section) {
    for (const ParamSpec& p : scene_params()) {
        if (p.section != section || !p.used_by(session.scene().sonar.kind)) continue;
        const json cur = p.get(session.scene());
        if (p.type == ParamType::Vec3) {
            Vec3d v = cur.get<Vec3d>();
            if (drag3(p, v)) session.set(p.key, v);
            continue;
        }
        if (p.type == ParamType::Enum) {
            const std::string now = cur.get<std::string>();
            const std::string label = field_label(w, p.label_text(), p.key);
            const bool open = ImGui::BeginCombo(label.c_str(), now.c_str());
            remember_rect(w, p.key); // the combo itself (what `move_to KEY` in a script aims at)
            if (open) {
                // The presets of the scene's kind of sonar.
                for (auto& c : p.key == "sonar.device" ? device_choices(kind_name(session.scene().sonar.kind))
                                                       : p.choices)
                    if (ImGui::Selectable(c.c_str(), c == now)) session.set(p.key, c);
                ImGui::EndCombo();
            }
            help_tooltip(p);
            continue;
        }
        if (p.type == ParamType::Bool) {
            bool on = cur.get<bool>();
            if (ImGui::Checkbox((p.label_text() + "##" + p.key).c_str(), &on)) session.set(p.key, on);
            help_tooltip(p);
            continue;
        }
        if (p.optional) { // absent (null) or a value: a checkbox, then the slider when present
            bool on = !cur.is_null();
            if (ImGui::Checkbox((p.label_text() + "##on_" + p.key).c_str(), &on))
                session.set(p.key, on ? json(optional_default(session.scene(), p)) : json(nullptr));
            help_tooltip(p);
            if (cur.is_null()) continue;
        }
        double v = 0;
        if (slider(w, p, cur.get<double>(), v))
            session.set(p.key, p.type == ParamType::Integer ? json(int(v)) : json(v));
    }
}

void pose_section(Session& session) {
    for (const ParamSpec& p : scene_params()) {
        if (p.section != Section::Pose) continue;
        Vec3d v = p.get(session.scene()).get<Vec3d>();
        if (drag3(p, v)) session.set(p.key, v);
    }
    if (is_paper_fig9_scene(session.scene())) { // the paper's poses mean nothing in other scenes
        if (ImGui::Button("Fig. 9 pose 1")) session.edit([](SceneDesc& s) { s.sonar.pose = Pose{}; });
        same_line_if_fits("Fig. 9 pose 2");
        if (ImGui::Button("Fig. 9 pose 2")) session.edit([](SceneDesc& s) { s.sonar.pose = kFig9Pose2; });
    }
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
    ImGui::TextWrapped("In 3D, drag the sonar's housing or its yellow handle to move it; Shift: up/down, "
                       "Ctrl: yaw/pitch, Ctrl+Shift: roll; Alt: fine.");
    ImGui::PopStyleColor();
}

void material_section(Session& session, ControlsUi& ui) {
    const SceneDesc& s = session.scene();
    const int n = int(s.objects.size());
    const bool water = s.water.surface_height_m.has_value();
    if (ui.selected >= n) ui.selected = n - 1;
    if (ui.selected == kSurfacePart && !water) ui.selected = kSeafloorPart;
    if (ui.selected == kSeafloorPart && !s.seafloor)
        ui.selected = n > 0 ? 0 : water ? kSurfacePart : kSeafloorPart;
    auto name = [&](int i) {
        if (i == kNothingSelected) return std::string("none");
        if (i == kSurfacePart) return std::string("water surface");
        if (i < 0) return std::string("seafloor");
        return object_label(s, size_t(i));
    };
    ControlsWidgets& w = ui.widgets;
    if (ImGui::BeginCombo(field_label(w, "surface", "surface").c_str(), name(ui.selected).c_str())) {
        if (s.seafloor && ImGui::Selectable("seafloor", ui.selected == kSeafloorPart))
            ui.selected = kSeafloorPart;
        if (water && ImGui::Selectable("water surface", ui.selected == kSurfacePart))
            ui.selected = kSurfacePart;
        for (int i = 0; i < n; ++i) {
            if (ImGui::Selectable(name(i).c_str(), ui.selected == i)) ui.selected = i;
            if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", object_tooltip(s, size_t(i)).c_str());
        }
        ImGui::EndCombo();
    } else if (ImGui::IsItemHovered() && ui.selected >= 0) {
        ImGui::SetTooltip("%s", object_tooltip(s, size_t(ui.selected)).c_str());
    }
    if (ui.selected == kNothingSelected) {
        ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
        ImGui::TextWrapped(
            "Click an object or the floor in 3D (or choose a surface above) to edit its material; "
            "a selected object can then be dragged.");
        ImGui::PopStyleColor();
        return;
    }
    if (ui.selected == kSeafloorPart && !s.seafloor) return;
    const bool surface = ui.selected == kSurfacePart;
    const Material& m = *material_of(s, ui.selected);
    const std::string prefix = material_prefix(ui.selected);
    const ValueSpec& preset = material_preset_param(); // a combo box of the presets' names
    if (ImGui::BeginCombo(field_label(w, preset.label_text(), prefix + preset.key).c_str(),
                          m.preset.c_str())) {
        for (auto& c : preset.choices)
            if (ImGui::Selectable(c.c_str(), c == m.preset)) session.set(prefix + preset.key, c);
        ImGui::EndCombo();
    }
    help_tooltip(preset);
    for (const MaterialSpec& spec : material_params()) {
        if (surface && spec.optional) continue; // reflection_db: the surface is always a mirror (roughness)
        double v = 0;
        ImGui::PushID(spec.key.c_str());
        const bool present = std::isfinite(m.*(spec.field));
        if (spec.optional) { // reflection_db: a checkbox (a mirror or not), then its slider
            bool on = present;
            if (ImGui::Checkbox((spec.label_text() + "##on").c_str(), &on))
                session.set(prefix + spec.key, on ? json(3.0) : json(nullptr));
            help_tooltip(spec);
        }
        if ((present || !spec.optional) && slider(w, spec, m.*(spec.field), v))
            session.set(prefix + spec.key, v);
        ImGui::PopID();
    }
    if (ui.selected >= 0) {
        const ObjectDesc& o = s.objects[size_t(ui.selected)];
        const std::string key = part_prefix(ui.selected);
        for (const ObjectSpec& p : object_params()) {
            if (p.section != Section::Object) continue;
            const json cur = p.get(o);
            if (p.type == ParamType::Vec3) {
                Vec3d v = cur.get<Vec3d>();
                if (drag3(p, v)) session.set(key + p.key, v);
                if (p.key == "scale" && ImGui::IsItemHovered())
                    ImGui::SetTooltip("In 3D: Alt+drag the object scales it");
            } else if (double v = 0; slider(w, p, cur.get<double>(), v)) {
                session.set(key + p.key, v);
            }
        }
        if (ImGui::Button("Remove object")) {
            const int i = ui.selected;
            session.edit([i](SceneDesc& sc) { sc.objects.erase(sc.objects.begin() + i); });
        }
    }
}

constexpr float kMostFooterShare = 0.25f;

void footer(Session& session) {
    if (!session.error().empty()) {
        ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.45f, 0.4f, 1.0f));
        ImGui::TextWrapped("%s", session.error().c_str());
        ImGui::PopStyleColor();
        if (ImGui::SmallButton("dismiss")) session.clear_error();
    }
    if (!session.status().empty()) {
        ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
        ImGui::TextWrapped("%s", session.status().c_str());
        ImGui::PopStyleColor();
    }
}

float footer_height(const Session& session, float width) {
    const ImGuiStyle& st = ImGui::GetStyle();
    float h = 0;
    if (!session.error().empty())
        h += ImGui::CalcTextSize(session.error().c_str(), nullptr, false, width).y + ImGui::GetFrameHeight() +
             2 * st.ItemSpacing.y;
    if (!session.status().empty())
        h += ImGui::CalcTextSize(session.status().c_str(), nullptr, false, width).y + st.ItemSpacing.y;
    return h > 0 ? h + st.ItemSpacing.y + 2 * st.WindowPadding.y : 0;
}

} // namespace

void draw_controls_panel(const Rect& area, Session& session, ControlsUi& ui, TrajectoryUi& trajectory) {
    ImGui::SetNextWindowPos(ImVec2(area.x, area.y));
    ImGui::SetNextWindowSize(ImVec2(area.w, area.h));
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                                   ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoTitleBar |
                                   ImGuiWindowFlags_NoBringToFrontOnFocus | ImGuiWindowFlags_NoBackground |
                                   ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse;
    ImGui::Begin("Controls", nullptr, flags);
    ui.widgets.item_rects.clear(); // this frame's, as drawn
    // The footer (error, status) takes at most a quarter of the panel, scrolling beyond: a long message
    // never hides the sections' widgets.
    float fh = footer_height(session, ImGui::GetContentRegionAvail().x);
    const bool footer_scrolls = fh > kMostFooterShare * ImGui::GetContentRegionAvail().y;
    if (footer_scrolls) fh = kMostFooterShare * ImGui::GetContentRegionAvail().y;
    ImGui::BeginChild("##sections", ImVec2(0, -fh), false);
    const float avail = ImGui::GetContentRegionAvail().x - ImGui::GetStyle().ScrollbarSize,
                label_w = widest_label();
    ControlsWidgets& w = ui.widgets;
    w.labels_above = label_w > 0.5f * avail;
    ImGui::PushItemWidth(w.labels_above ? -1.0f : -label_w);
    draw_readout(session, ui.frame_ms);
    const std::string snapshot = "Snapshot (" + shortcut_text(KeyAction::Snapshot) + ")"; // the bindings' key
    if (is_paper_fig9_scene(session.scene())) {
        if (ImGui::Button("Reset to paper values")) session.reset_to_paper();
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("Every parameter and material back to Tables I-II (the pose is kept)");
        same_line_if_fits(snapshot.c_str());
    }
    if (ImGui::Button(snapshot.c_str())) ui.want_snapshot = true;

    // The table's sections (param_spec.hpp), in the panel's order; the first ones open.
    const ImGuiTreeNodeFlags open = ImGuiTreeNodeFlags_DefaultOpen;
    if (ImGui::CollapsingHeader(section_title(Section::Pose), open)) pose_section(session);
    for (Section sec : {Section::Sonar, Section::Water})
        if (ImGui::CollapsingHeader(section_title(sec), open)) section_params(w, session, sec);
    if (ImGui::CollapsingHeader(section_title(Section::Material), open)) material_section(session, ui);
    if (ImGui::CollapsingHeader(section_title(Section::Display), open))
        section_params(w, session, Section::Display);
    for (Section sec : {Section::Sensor, Section::Sampling, Section::Motion})
        if (ImGui::CollapsingHeader(section_title(sec))) section_params(w, session, sec);
    if (ImGui::CollapsingHeader("Trajectory"))
        if (auto p = trajectory.draw(session)) session.edit([&](SceneDesc& s) { s.sonar.pose = *p; });
    if (ImGui::CollapsingHeader("Files")) {
        if (ImGui::Button("Open scene...")) ui.want_open = true;
        same_line_if_fits("Add mesh...");
        if (ImGui::Button("Add mesh...")) ui.want_add_mesh = true;
        if (ImGui::Button("Save scene...")) ui.want_save = true;
        const std::string where =
            (std::filesystem::absolute(ui.snapshot_dir) / "").lexically_normal().parent_path().string();
        ImGui::TextWrapped("Snapshots (%s) go to %s", shortcut_text(KeyAction::Snapshot).c_str(),
                           where.c_str());
        if (ImGui::Button("Snapshot folder...")) ui.want_snapshot_dir = true;
        ImGui::Checkbox("annotated PNG too", &ui.annotated_snapshot);
        ImGui::TextWrapped("Drop a scene (.json) or mesh (%s) on the window",
                           mesh_extensions_text(" ").c_str());
    }
    if (ImGui::CollapsingHeader("View")) {
        ImGui::Checkbox("show traced hits", &ui.show_hits);
        if (ImGui::Button(("Reset camera (" + shortcut_text(KeyAction::ResetCamera) + ")").c_str()))
            ui.want_reset_camera = true;
        ImGui::SliderFloat(field_label(w, "UI scale", "uiscale").c_str(), &ui.ui_scale, 0.75f, 2.5f, "%.2f");
    }
    ImGui::PopItemWidth();
    ImGui::EndChild();
    if (footer_scrolls) ImGui::BeginChild("##footer", ImVec2(0, 0), false);
    footer(session);
    if (footer_scrolls) ImGui::EndChild();
    ImGui::End();
}

} // namespace sonarsim::ui

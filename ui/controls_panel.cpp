#include "controls_panel.hpp"

#include "param_ranges.hpp"

#include "core/physics.hpp"

#include <imgui.h>
#include <imgui_stdlib.h>

namespace sonarsim::ui {
namespace {

void help_tooltip(const ValueSpec& spec) {
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("%s\n%s: %s\nCtrl+click to type a value", spec.help.c_str(), spec.key.c_str(),
                          allowed_text(spec).c_str());
}

/// One slider for a number or integer spec. Returns true with `value` set when edited.
bool slider(const ValueSpec& spec, double current, double& value) {
    const SliderRange r = slider_range(spec);
    const std::string label = param_label(spec) + "##" + spec.key;
    ImGuiSliderFlags flags = r.logarithmic ? ImGuiSliderFlags_Logarithmic : 0;
    bool changed = false;
    if (spec.type == ParamType::Integer) {
        int v = int(current), lo = int(r.lo), hi = int(r.hi);
        changed = ImGui::SliderScalar(label.c_str(), ImGuiDataType_S32, &v, &lo, &hi, "%d", flags);
        value = v;
    } else {
        double v = current;
        const double span = r.hi - r.lo;
        const char* fmt = span >= 500 ? "%.0f" : span >= 20 ? "%.1f" : "%.3g";
        changed = ImGui::SliderScalar(label.c_str(), ImGuiDataType_Double, &v, &r.lo, &r.hi, fmt,
                                      flags | ImGuiSliderFlags_NoRoundToFormat);
        value = v;
    }
    help_tooltip(spec);
    return changed;
}

void section_params(Session& session, const std::string& section) {
    for (const ParamSpec& p : scene_params()) {
        if (param_section(p) != section) continue;
        const json cur = p.get(session.scene());
        if (p.type == ParamType::Enum) {
            const std::string now = cur.get<std::string>();
            const std::string label = param_label(p) + "##" + p.key;
            if (ImGui::BeginCombo(label.c_str(), now.c_str())) {
                for (auto& c : p.choices)
                    if (ImGui::Selectable(c.c_str(), c == now)) session.set(p.key, c);
                ImGui::EndCombo();
            }
            help_tooltip(p);
            continue;
        }
        if (p.type == ParamType::Bool) {
            bool on = cur.get<bool>();
            if (ImGui::Checkbox((param_label(p) + "##" + p.key).c_str(), &on)) session.set(p.key, on);
            help_tooltip(p);
            continue;
        }
        double v = 0;
        if (slider(p, cur.get<double>(), v))
            session.set(p.key, p.type == ParamType::Integer ? json(int(v)) : json(v));
    }
}

void pose_section(Session& session) {
    Pose pose = session.scene().sonar.pose;
    bool changed = ImGui::DragScalarN("position [m]", ImGuiDataType_Double, pose.position_m.data(), 3, 0.005f,
                                      nullptr, nullptr, "%.3f");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("x, y, z of the sonar (world, z up); drag or Ctrl+click");
    changed |= ImGui::DragScalarN("roll pitch yaw [deg]", ImGuiDataType_Double, pose.orientation_deg.data(),
                                  3, 0.2f, nullptr, nullptr, "%.2f");
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("R = Rz(yaw) Ry(pitch) Rx(roll); positive pitch looks down");
    if (changed)
        session.edit([&](SceneDesc& s) {
            apply_setting(s, "sonar.position", pose.position_m, "pose");
            apply_setting(s, "sonar.orientation_deg", pose.orientation_deg, "pose");
        });
    if (ImGui::Button("Fig. 9 pose 1")) session.edit([](SceneDesc& s) { s.sonar.pose = Pose{}; });
    ImGui::SameLine();
    if (ImGui::Button("Fig. 9 pose 2"))
        session.edit([](SceneDesc& s) {
            s.sonar.pose.position_m = {0.84, 2.42, 0.90};
            s.sonar.pose.orientation_deg = {6.88, 28.07, -41.25};
        });
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
    ImGui::TextWrapped("In 3D, drag the frustum to move the sonar; Shift: up/down, Ctrl: yaw/pitch, "
                       "Ctrl+Shift: roll.");
    ImGui::PopStyleColor();
}

void material_section(Session& session, ControlsUi& ui) {
    const SceneDesc& s = session.scene();
    const int n = int(s.objects.size());
    if (ui.selected >= n) ui.selected = n - 1;
    if (ui.selected < 0 && !s.seafloor) ui.selected = n > 0 ? 0 : -1;
    auto name = [&](int i) {
        if (i < 0) return std::string("seafloor");
        const ObjectDesc& o = s.objects[size_t(i)];
        return "object " + std::to_string(i) + (o.box_m ? " (box)" : " (" + o.mesh + ")");
    };
    if (ImGui::BeginCombo("surface", name(ui.selected).c_str())) {
        if (s.seafloor && ImGui::Selectable("seafloor", ui.selected < 0)) ui.selected = -1;
        for (int i = 0; i < n; ++i)
            if (ImGui::Selectable(name(i).c_str(), ui.selected == i)) ui.selected = i;
        ImGui::EndCombo();
    }
    if (ui.selected < 0 && !s.seafloor) return;
    const Material& m = ui.selected < 0 ? s.seafloor->material : s.objects[size_t(ui.selected)].material;
    const std::string prefix =
        ui.selected < 0 ? "seafloor.material." : "objects." + std::to_string(ui.selected) + ".material.";
    for (const MaterialSpec& spec : material_params()) {
        double v = 0;
        ImGui::PushID(spec.key.c_str());
        if (slider(spec, m.*(spec.field), v)) session.set(prefix + spec.key, v);
        ImGui::PopID();
    }
    if (ui.selected >= 0) {
        Vec3d pos = s.objects[size_t(ui.selected)].position_m;
        if (ImGui::DragScalarN("object position [m]", ImGuiDataType_Double, pos.data(), 3, 0.005f, nullptr,
                               nullptr, "%.3f"))
            session.set("objects." + std::to_string(ui.selected) + ".position", pos);
        Vec3d rot = s.objects[size_t(ui.selected)].orientation_deg;
        if (ImGui::DragScalarN("object rpy [deg]", ImGuiDataType_Double, rot.data(), 3, 0.5f, nullptr,
                               nullptr, "%.1f"))
            session.set("objects." + std::to_string(ui.selected) + ".orientation_deg", rot);
        if (ImGui::Button("Remove object")) {
            const int i = ui.selected;
            session.edit([i](SceneDesc& sc) { sc.objects.erase(sc.objects.begin() + i); });
        }
    }
}

void stats_section(Session& session, const ControlsUi& ui) {
    const SceneDesc& s = session.scene();
    ImGui::Text("alpha = %.3f dB/m",
                absorption_db_per_m(s.sonar.frequency_khz, s.water.temperature_c, s.water.depth_m));
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("Absorption (eq. 7) at f, T, D; the paper's Table II gives 3.04 dB/m");
    ImGui::Text("frame %.1f ms", ui.frame_ms);
    if (const RenderResult* r = session.shown()) {
        const Frame& f = *r->frame;
        ImGui::SameLine();
        ImGui::Text("  image %.1f ms%s", r->wall_ms, f.preview() ? " (preview)" : "");
        ImGui::TextDisabled("trace %.1f  shade %.1f  map %.1f ms", f.trace_ms, f.shade_ms, f.image_ms);
        ImGui::TextDisabled("%llu rays", static_cast<unsigned long long>(f.hits().rays_traced));
    } else {
        ImGui::SameLine();
        ImGui::TextDisabled("  image: rendering...");
    }
}

} // namespace

void draw_controls_panel(const Rect& area, Session& session, ControlsUi& ui) {
    ImGui::SetNextWindowPos(ImVec2(area.x, area.y));
    ImGui::SetNextWindowSize(ImVec2(area.w, area.h));
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                                   ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoTitleBar |
                                   ImGuiWindowFlags_NoBringToFrontOnFocus | ImGuiWindowFlags_NoBackground;
    ImGui::Begin("Controls", nullptr, flags);
    ImGui::PushItemWidth(-150);
    stats_section(session, ui);
    if (!session.error().empty()) {
        ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.45f, 0.4f, 1.0f));
        ImGui::TextWrapped("%s", session.error().c_str());
        ImGui::PopStyleColor();
        if (ImGui::SmallButton("dismiss")) session.clear_error();
    }
    if (!session.status().empty()) ImGui::TextDisabled("%s", session.status().c_str());
    if (ImGui::Button("Reset to paper values")) session.reset_to_paper();
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("Every parameter and material back to Tables I-II (the pose is kept)");
    ImGui::SameLine();
    if (ImGui::Button("Snapshot (S)")) ui.want_snapshot = true;

    if (ImGui::CollapsingHeader("Pose", ImGuiTreeNodeFlags_DefaultOpen)) pose_section(session);
    if (ImGui::CollapsingHeader("Sonar", ImGuiTreeNodeFlags_DefaultOpen)) section_params(session, "Sonar");
    if (ImGui::CollapsingHeader("Water", ImGuiTreeNodeFlags_DefaultOpen)) section_params(session, "Water");
    if (ImGui::CollapsingHeader("Material", ImGuiTreeNodeFlags_DefaultOpen)) material_section(session, ui);
    if (ImGui::CollapsingHeader("Display", ImGuiTreeNodeFlags_DefaultOpen))
        section_params(session, "Display");
    if (ImGui::CollapsingHeader("Sensor")) section_params(session, "Sensor");
    if (ImGui::CollapsingHeader("Sampling")) section_params(session, "Sampling");
    if (ImGui::CollapsingHeader("Files")) {
        if (ImGui::Button("Open scene...")) ui.want_open = true;
        ImGui::SameLine();
        if (ImGui::Button("Add mesh...")) ui.want_add_mesh = true;
        ImGui::SameLine();
        if (ImGui::Button("Save scene...")) ui.want_save = true;
        ImGui::InputText("snapshot folder", &ui.snapshot_dir);
        ImGui::TextDisabled("Drop a scene (.json) or mesh (.obj .ply .stl .off) on the window");
    }
    if (ImGui::CollapsingHeader("View")) {
        ImGui::Checkbox("show traced hits", &ui.show_hits);
        if (ImGui::Button("Reset camera (F)")) ui.want_reset_camera = true;
    }
    ImGui::PopItemWidth();
    ImGui::End();
}

} // namespace sonarsim::ui

#include "ui/gl/trajectory_panel.hpp"

#include "core/base/errors.hpp"

#include <imgui.h>
#include <imgui_stdlib.h>

namespace sonarsim::ui {

void TrajectoryUi::toggle_record(const Pose& now) {
    playing = false;
    recording = !recording;
    if (recording) {
        track.clear();
        record_t_s = 0;
        track.add(0, now);
    }
}

void TrajectoryUi::toggle_play() {
    recording = false;
    if (track.size() < 2) return;
    playing = !playing;
    if (playing && t_s >= track.samples().back().t_s) t_s = track.samples().front().t_s;
}

std::optional<Pose> TrajectoryUi::update(const Pose& now, double dt_s) {
    if (recording) {
        record_t_s += dt_s;
        track.add(record_t_s, now);
    }
    if (!playing || track.empty()) return std::nullopt;
    t_s += dt_s;
    if (t_s >= track.samples().back().t_s) t_s = track.samples().back().t_s, playing = false;
    return track.at(t_s);
}

std::optional<Pose> TrajectoryUi::draw(Session& session) {
    std::optional<Pose> out;
    if (ImGui::Button(recording ? "Stop recording (R)" : "Record (R)"))
        toggle_record(session.scene().sonar.pose);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Records the sonar's pose every frame while it moves");
    if (ImGui::Button(playing ? "Pause (Space)" : "Play (Space)")) toggle_play();
    ImGui::Text("%zu poses, %.2f s", track.size(), track.duration_s());
    if (!track.empty()) {
        const double lo = track.samples().front().t_s, hi = track.samples().back().t_s;
        double t = std::clamp(t_s, lo, hi);
        ImGui::SetNextItemWidth(-1);
        if (ImGui::SliderScalar("##time", ImGuiDataType_Double, &t, &lo, &hi, "t = %.2f s")) {
            t_s = t, playing = false;
            out = track.at(t_s);
        }
    }
    ImGui::SetNextItemWidth(-1);
    ImGui::InputText("##trajectory file", &path);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("CSV: %s (sonarsim batch --trajectory)", kTrajectoryHeader);
    if (ImGui::Button("Save CSV")) {
        try {
            save_trajectory(track, path);
            session.set_status("wrote " + path);
        } catch (const std::exception& e) {
            session.set_error(e.what());
        }
    }
    ImGui::SameLine();
    if (ImGui::Button("Load CSV")) {
        try {
            track = load_trajectory(path);
            t_s = track.empty() ? 0 : track.samples().front().t_s;
            if (!track.empty()) out = track.at(t_s);
            session.set_status("loaded " + path);
        } catch (const InputError& e) {
            session.set_error(e.what());
        }
    }
    return out;
}

} // namespace sonarsim::ui

// The controls panel (ImGui): sliders generated from core's parameter table, numeric pose, the material of
// the selected object, files, snapshot, timings and errors.
#pragma once
#include "core/scene/scene_parts.hpp"
#include "ui/model/layout.hpp"
#include "ui/model/session.hpp"
#include "ui/model/view_controller.hpp"
#include "ui/gl/trajectory_panel.hpp"

#include <map>
#include <string>

namespace sonarsim::ui {

/// What the panel's widgets keep from one frame to the next.
struct ControlsWidgets {
    /// Shift held while a slider is dragged: that slider (an ImGuiID; 0: none), its value and the mouse's x
    /// when Shift went down.
    unsigned fine_id = 0;
    double fine_base = 0;
    float fine_mouse_x0 = 0;
    /// The part of each parameter's widget on screen last frame (key -> window px), for `--script move_to`:
    /// none for a widget scrolled out of the panel or in a closed section.
    std::map<std::string, Rect> item_rects;
    /// Labels go beside the fields when the widest fits beside a field of half the panel, else above them.
    bool labels_above = false;
};

struct ControlsUi {
    int selected = kNothingSelected; ///< the part whose material is edited (scene_parts.hpp): an object,
                                     ///< kSeafloorPart, kSurfacePart
    bool show_hits = false;          ///< draw every traced hit in the 3D view
    std::string snapshot_dir = ".";
    double frame_ms = 0; ///< shown on screen
    // Requests raised by the panel, handled by the viewer.
    bool want_snapshot = false, want_open = false, want_add_mesh = false, want_save = false;
    bool want_snapshot_dir = false; ///< the folder dialog for snapshot_dir
    bool want_reset_camera = false;
    float ui_scale = 1.0f;          ///< the user's UI scale, times the monitor's content scale
    bool annotated_snapshot = true; ///< snapshots also write PREFIX_annotated.png (the panel as on screen)
    ControlsWidgets widgets;
};

/// The panel: its sections scroll; errors and status stay visible in a footer below them.
void draw_controls_panel(const Rect& area, Session& session, ControlsUi& ui, TrajectoryUi& trajectory);

} // namespace sonarsim::ui

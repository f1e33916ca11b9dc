// Non-GL layout of the viewer window: where the controls, the 3D view, the sonar image, its colour bar and
// the A-scan go for a given window size. Shared by the viewer and the screenshot tests.
#pragma once

namespace sonarsim::ui {

struct Rect {
    float x = 0, y = 0, w = 0, h = 0;
    bool contains(double px, double py) const { return px >= x && px < x + w && py >= y && py < y + h; }
};

/// Height of the main menu bar at UI scale 1 (ImGui's default font: 13 px + 2 x 3 px frame padding).
constexpr float kMenuBarHeight = 19.0f;

struct ViewerLayout {
    Rect controls; ///< left: parameters, pose, materials, files
    Rect view3d;   ///< middle: the 3D view
    Rect sonar;    ///< right: the sonar image panel
};
/// `scale`: the UI scale (monitor content scale x the user's setting); panels widen with it.
ViewerLayout viewer_layout(int width_px, int height_px, float scale = 1.0f);

/// The largest rectangle of aspect w/h inside `box`, centred horizontally, at the top.
Rect fit_rect(const Rect& box, double w_over_h);

struct SonarPanelLayout {
    Rect image;    ///< the fan (or raw polar image), aspect-correct
    Rect colorbar; ///< the dB colour bar beside it
    Rect ascan;    ///< the A-scan plot below
};
/// Layout inside the sonar panel for an image of aspect w/h.
/// Room is left for the labels: range labels left of the image, bearings above and below, the colour bar's
/// ticks right of it.
SonarPanelLayout sonar_panel_layout(const Rect& panel, double image_w_over_h, float scale = 1.0f);

} // namespace sonarsim::ui

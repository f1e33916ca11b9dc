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
/// `scale`: the UI scale (monitor content scale x the user's setting); panels widen with it. `fan_w_over_h`:
/// the aspect of the sonar's fan; a wide fan widens the sonar panel (up to 45% of the window, keeping the 3D
/// view at least 30% and 480 px) so that the fan can fill it.
ViewerLayout viewer_layout(int width_px, int height_px, float scale = 1.0f, double fan_w_over_h = 1.0);

/// The largest rectangle of aspect w/h inside `box`, centred horizontally, at the top.
Rect fit_rect(const Rect& box, double w_over_h);

} // namespace sonarsim::ui

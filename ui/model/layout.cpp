#include "ui/model/layout.hpp"

#include "ui/model/panel_layout.hpp"

#include <algorithm>

namespace sonarsim::ui {
namespace {
constexpr float kControlsW = 310, kSonarW = 430;
}

ViewerLayout viewer_layout(int w, int h, float k, double fan_aspect) {
    const float W = float(w), H = float(h) - kMenuBarHeight * k, y = kMenuBarHeight * k;
    // Large windows give the sonar image more room; small ones keep the 3D view at least a quarter.
    const float cw = std::min(kControlsW * k, W * 0.34f);
    const float cap = std::min(0.45f * W, W - cw - std::max(0.3f * W, 480 * k)); // the 3D view keeps room
    const float sw = std::max(std::min(std::max(kSonarW * k, W * 0.3f), W * 0.4f),
                              std::min(sonar_panel_width_wanted(h, fan_aspect, k), cap));
    ViewerLayout L;
    L.controls = {0, y, cw, H};
    L.sonar = {W - sw, y, sw, H};
    L.view3d = {cw, y, std::max(1.0f, W - cw - sw), H};
    return L;
}

Rect fit_rect(const Rect& box, double aspect) {
    float w = box.w, h = float(w / aspect);
    if (h > box.h) h = box.h, w = float(h * aspect);
    return {box.x + (box.w - w) / 2, box.y, std::max(1.0f, w), std::max(1.0f, h)};
}

} // namespace sonarsim::ui

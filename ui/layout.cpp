#include "layout.hpp"

#include <algorithm>

namespace sonarsim::ui {
namespace {
constexpr float kControlsW = 310, kSonarW = 430, kHeaderH = 64, kAscanH = 200, kBarW = 16, kBarLabelsW = 46,
                kPad = 8;
}

ViewerLayout viewer_layout(int w, int h) {
    const float W = float(w), H = float(h) - kMenuBarHeight, y = kMenuBarHeight;
    const float cw = std::min(kControlsW, W * 0.3f), sw = std::min(kSonarW, W * 0.4f);
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

SonarPanelLayout sonar_panel_layout(const Rect& p, double aspect) {
    SonarPanelLayout L;
    const Rect box{p.x + kPad, p.y + kHeaderH, p.w - 2 * kPad - kBarW - kBarLabelsW - kPad,
                   p.h - kHeaderH - kAscanH - 2 * kPad};
    L.image = fit_rect(box, aspect);
    L.colorbar = {box.x + box.w + kPad, L.image.y, kBarW, L.image.h};
    L.ascan = {p.x + kPad, p.y + p.h - kAscanH - kPad, p.w - 2 * kPad, kAscanH};
    return L;
}

} // namespace sonarsim::ui

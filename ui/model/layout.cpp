#include "ui/model/layout.hpp"

#include <algorithm>

namespace sonarsim::ui {
namespace {
constexpr float kControlsW = 310, kSonarW = 430, kHeaderH = 78, kAscanH = 200, kBarW = 16, kBarLabelsW = 40,
                kPad = 8, kRangeLabelsW = 34, kLabelH = 16;
}

ViewerLayout viewer_layout(int w, int h, float k) {
    const float W = float(w), H = float(h) - kMenuBarHeight * k, y = kMenuBarHeight * k;
    // Large windows give the sonar image more room; small ones keep the 3D view at least a quarter.
    const float cw = std::min(kControlsW * k, W * 0.34f),
                sw = std::min(std::max(kSonarW * k, W * 0.3f), W * 0.4f);
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

SonarPanelLayout sonar_panel_layout(const Rect& p, double aspect, float k) {
    SonarPanelLayout L;
    const float ascan_h = std::min(std::max(kAscanH * k, 0.25f * p.h), 0.34f * p.h);
    const Rect box{p.x + (kPad + kRangeLabelsW) * k, p.y + (kHeaderH + kLabelH) * k,
                   p.w - (3 * kPad + kRangeLabelsW + kBarW + kBarLabelsW) * k,
                   p.h - (kHeaderH + 2 * kLabelH + 2 * kPad) * k - ascan_h};
    L.image = fit_rect(box, aspect);
    L.colorbar = {box.x + box.w + kPad * k, L.image.y, kBarW * k, L.image.h};
    L.ascan = {p.x + kPad * k, p.y + p.h - ascan_h - kPad * k, p.w - 2 * kPad * k, ascan_h};
    return L;
}

} // namespace sonarsim::ui

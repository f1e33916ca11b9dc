#include "ui/model/panel_layout.hpp"

#include "ui/model/image_views.hpp"
#include "core/display/polar_layout.hpp"

#include "core/data/pose.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace sonarsim::ui {
namespace {

constexpr float kPad = 8, kBarW = 16, kTickLen = 4, kGap = 4, kAscanMinFrac = 0.22f, kAscanMinH = 150;

bool overlaps(const Rect& a, const Rect& b, float gap = 0) {
    return a.x < b.x + b.w + gap && b.x < a.x + a.w + gap && a.y < b.y + b.h + gap && b.y < a.y + a.h + gap;
}
Rect unite(const Rect& a, const Rect& b) {
    const float x0 = std::min(a.x, b.x), y0 = std::min(a.y, b.y);
    return {x0, y0, std::max(a.x + a.w, b.x + b.w) - x0, std::max(a.y + a.h, b.y + b.h) - y0};
}
/// A w x h box just outside point p in direction u (unit): its nearest edge `gap` from p along u.
Rect box_beyond(const glm::dvec2& p, const glm::dvec2& u, float w, float h, float gap) {
    const double reach = gap + std::abs(u.x) * w / 2 + std::abs(u.y) * h / 2;
    const glm::dvec2 c = p + u * reach;
    return {float(c.x) - w / 2, float(c.y) - h / 2, w, h};
}
std::string deg_text(double a) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%+g deg", std::abs(a) < 1e-9 ? 0.0 : a);
    return buf;
}
std::string m_text(double r) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g m", r);
    return buf;
}

struct Labels {
    std::vector<PanelLabel> bearings, ranges;
    std::vector<double> bearing_deg, range_m;
    Rect bounds; ///< image and labels
};

/// Keeps a candidate unless it overlaps a kept label or (`fan`) the fan; in priority order.
template <class Inside>
void keep_if_free(std::vector<PanelLabel>& kept, std::vector<double>& values,
                  const std::vector<PanelLabel>& others, const PanelLabel& cand, double value, float gap,
                  Inside inside) {
    for (const std::vector<PanelLabel>* list : {static_cast<const std::vector<PanelLabel>*>(&kept), &others})
        for (const PanelLabel& k : *list)
            if (overlaps(k.box, cand.box, gap)) return;
    // The fan: a grid of points over the box must all be outside it.
    for (int i = 0; i <= 4; ++i)
        for (int j = 0; j <= 2; ++j)
            if (inside(cand.box.x + cand.box.w * float(i) / 4, cand.box.y + cand.box.h * float(j) / 2))
                return;
    kept.push_back(cand), values.push_back(value);
}

/// The labels of an image of width w placed with its top-left corner at (x, y).
Labels place_labels(const PanelContent& c, const SectorLayout& sector, float x, float y, float w,
                    const TextMetrics& t, FanOnScreen& fan) {
    const SonarParams& s = c.sonar;
    const float h = w * float(sector.height()) / float(sector.width());
    Labels L;
    L.bounds = {x, y, w, h};
    const float th = t.line_h, gap = kGap;
    const SonarGrid& grid = sector.grid();
    const double port = grid.port_edge_deg(), starboard = grid.starboard_edge_deg();
    const double astep = nice_step(grid.fov_deg, 6), rstep = nice_step(grid.window_m(), 5);
    // Bearings: 0 first, then from the edges inwards (the extremes matter most), each where it fits.
    std::vector<double> angles;
    for (double a = std::floor(port / astep + 1e-9) * astep; a >= starboard - 1e-9; a -= astep)
        angles.push_back(a);
    std::stable_sort(angles.begin(), angles.end(), [](double a, double b) {
        auto rank = [](double v) { return std::abs(v) < 1e-9 ? -1.0 : -std::abs(v); };
        return rank(a) < rank(b);
    });
    std::vector<double> rings;
    for (double r = std::ceil(s.range_min_m / rstep - 1e-9) * rstep; r <= s.range_max_m + 1e-9; r += rstep)
        if (r > 0) rings.push_back(r);
    if (c.polar) {
        const PolarLayout PL(grid);
        auto x_of = [&](double a) { return x + float(PL.u_of_azimuth_deg(a)) * w; };
        auto y_of = [&](double r) { return y + float(PL.v_of_range_m(r)) * h; };
        auto none = [](float, float) { return false; };
        const Rect img{x, y, w, h};
        for (double a : angles) {
            const std::string txt = deg_text(a);
            const float tw = t.width(txt);
            keep_if_free(L.bearings, L.bearing_deg, {}, {txt, {x_of(a) - tw / 2, y - gap - th, tw, th}}, a,
                         gap, [&](float px, float py) { return img.contains(px, py); });
        }
        for (double r : rings) {
            const std::string txt = m_text(r);
            const float tw = t.width(txt);
            keep_if_free(L.ranges, L.range_m, L.bearings, {txt, {x - gap - tw, y_of(r) - th / 2, tw, th}}, r,
                         gap, none);
        }
    } else {
        fan.r_min_m = s.range_min_m, fan.r_max_m = s.range_max_m;
        fan.port_deg = port, fan.starboard_deg = starboard;
        double px0, py0, px1, py1;
        sector.polar_to_pixel(0, 0, px0, py0);
        sector.polar_to_pixel(1, 0, px1, py1);
        const double k = w / sector.width();
        fan.apex = {x + px0 * k, y + py0 * k};
        fan.px_per_m = (py0 - py1) * k;
        auto inside = [&](float px, float py) { return fan.contains(px, py); };
        // Bearings: beyond the arc, along the bearing; where that would widen the image (45 deg and more off
        // the boresight, the sides of a wide fan), above the arc within the image's width instead, so that
        // the fan, not its labels, takes the panel's width.
        const double R = fan.px_per_m * s.range_max_m;
        for (double a : angles) {
            const double ar = deg2rad(a);
            const std::string txt = deg_text(a);
            const float tw = t.width(txt);
            const glm::dvec2 p = fan.at(s.range_max_m, a);
            Rect box = box_beyond(p, {-std::sin(ar), -std::cos(ar)}, tw, th, gap);
            if (std::abs(a) >= 45 && (box.x < x || box.x + box.w > x + w)) {
                const float bx = std::clamp(float(p.x) - tw / 2, x, x + w - tw);
                // Its lower edge above the arc over the box's whole width: the arc is highest at the box's
                // point nearest the boresight.
                const double inner =
                    std::min(R, std::max({0.0, double(bx) - fan.apex.x, fan.apex.x - double(bx + tw)}));
                const double arc_y = fan.apex.y - std::sqrt(R * R - inner * inner);
                box = {bx, float(arc_y) - gap - th, tw, th};
            }
            keep_if_free(L.bearings, L.bearing_deg, {}, {txt, box}, a, gap, inside);
        }
        // Ranges: beside the port edge, outside the fan; the ones that would collide are left out.
        const double hr = deg2rad(port);
        const glm::dvec2 normal(-std::cos(hr), std::sin(hr));
        for (double r : rings) {
            const std::string txt = m_text(r);
            const Rect box = box_beyond(fan.at(r, port), normal, t.width(txt), th, gap);
            keep_if_free(L.ranges, L.range_m, L.bearings, {txt, box}, r, gap, inside);
        }
    }
    for (const auto* list : {&L.bearings, &L.ranges})
        for (const PanelLabel& l : *list) L.bounds = unite(L.bounds, l.box);
    return L;
}

} // namespace

glm::dvec2 FanOnScreen::at(double r, double a_deg) const {
    const double a = deg2rad(a_deg);
    return apex + px_per_m * r * glm::dvec2(-std::sin(a), -std::cos(a));
}

bool FanOnScreen::contains(double x, double y) const {
    const glm::dvec2 d = (glm::dvec2(x, y) - apex) / px_per_m;
    const double r = glm::length(d), a = rad2deg(std::atan2(-d.x, -d.y));
    return r >= r_min_m && r <= r_max_m && a <= port_deg && a >= starboard_deg;
}

std::string colorbar_title(const SceneDesc& scene) {
    const SensorParams& s = scene.sensor;
    if (s.model == SensorModel::Ideal) return "L_EN dB";
    static const char* tvg[] = {"no TVG", "TVG 20 log r", "TVG 30 log r", "TVG 40 log r"};
    char buf[96];
    std::snprintf(buf, sizeof buf, "device level dB (%s, gain %+g dB)", tvg[int(s.tvg)], s.gain_db);
    return buf;
}

int fan_height_to_form(double shown_h_px, const SonarGrid& grid) {
    const int full = grid.default_fan_height_px();
    if (!(shown_h_px < full)) return 0;
    const int h = std::max(256, 64 * int(std::ceil(shown_h_px / 64)));
    return h < full ? h : 0;
}

double fan_aspect(const SonarParams& s) {
    if (s.kind != SonarKind::Imaging) return 1.0; // a waterfall or a sweep: a panel about as wide as high
    const FanLayout fan = sonar_grid(s)->fan_layout(default_sector_height(s));
    return double(fan.width_px) / fan.height_px;
}

float sonar_panel_width_wanted(int window_h, double aspect, float k) {
    const float h = float(window_h) - kMenuBarHeight * k;
    const float image_h = h * (1 - kAscanMinFrac) - (kReadoutLines + 4) * 17 * k - 2 * kPad * k;
    // Beside the image: the colour bar and its ticks, the labels either side.
    return std::max(0.0f, image_h) * float(aspect) + 200 * k;
}

SonarPanelLayout sonar_panel_layout(const Rect& p, const PanelContent& c, const TextMetrics& t, float k) {
    SonarPanelLayout L;
    const float pad = kPad * k, th = t.line_h;
    const float header_h = th + 2 * 3 * k + 4 * k; // the view radio buttons and the colour map combo
    L.readout = {p.x + pad, p.y + header_h, p.w - 2 * pad, kReadoutLines * th + 2 * k};
    // The colour bar: at the right edge, its ticks right of it, its title on a row of its own above.
    char buf[32];
    float tick_w = 0;
    const double lo = std::min(c.lo_db, c.hi_db), hi = std::max(c.lo_db, c.hi_db);
    const double span = c.hi_db - c.lo_db;
    const double step = std::abs(span) > 1e-9 ? nice_step(std::abs(span), 6) : 1;
    std::vector<double> ticks;
    if (std::abs(span) > 1e-9)
        for (double v = std::ceil(lo / step - 1e-9) * step; v <= hi + 1e-9; v += step) {
            ticks.push_back(v);
            std::snprintf(buf, sizeof buf, "%g", v);
            tick_w = std::max(tick_w, t.width(buf));
        }
    const float bar_total = kBarW * k + kTickLen * k + 2 * k + tick_w; // the bar, its ticks and their labels
    const float bar_x_max = p.x + p.w - pad - bar_total;
    const float title_y = L.readout.y + L.readout.h + 2 * k;
    const float title_w = std::min(t.width(c.colorbar_title), p.w - 2 * pad);
    const float top =
        title_y + 1.5f * th + kGap * k; // the top tick's label reaches half a line above the bar

    // The image: the widest whose labels fit between the panel's left edge and the colour bar, above the
    // A-scan's least height.
    const float ascan_min = std::max(kAscanMinH * k, kAscanMinFrac * p.h);
    const Rect room{p.x + pad, top, bar_x_max - 2 * pad - (p.x + pad), p.y + p.h - pad - ascan_min - top};
    const SonarParams& s = c.sonar;
    const SectorLayout sector(s, c.fan_height_px > 0 ? c.fan_height_px : default_sector_height(s));
    FanOnScreen fan;
    auto fits = [&](float w) {
        const Labels l = place_labels(c, sector, 0, 0, w, t, fan);
        return l.bounds.w <= room.w && l.bounds.h <= room.h;
    };
    float lo_w = 8, hi_w = std::max(8.0f, room.w);
    if (fits(hi_w)) {
        lo_w = hi_w;
    } else {
        for (int i = 0; i < 30; ++i) {
            const float mid = 0.5f * (lo_w + hi_w);
            (fits(mid) ? lo_w : hi_w) = mid;
        }
    }
    const float w = std::floor(lo_w);
    const Labels rel = place_labels(c, sector, 0, 0, w, t, fan);
    // The image with its labels and the colour bar beside them, centred in the panel as one group.
    const float group_x = room.x + (room.w - rel.bounds.w) / 2;
    const float x = group_x - rel.bounds.x, y = room.y - rel.bounds.y;
    const float bar_x = group_x + rel.bounds.w + 2 * pad;
    const float title_x = std::max(p.x + pad, bar_x + bar_total - title_w);
    L.colorbar_title = {c.colorbar_title, {title_x, title_y, title_w, th}};
    const Labels l = place_labels(c, sector, x, y, w, t, L.fan);
    L.image = {x, y, w, w * float(sector.height()) / float(sector.width())};
    if (c.polar) L.fan = {};
    L.bearings = l.bearings, L.ranges = l.ranges, L.bearing_deg = l.bearing_deg, L.range_m = l.range_m;

    L.colorbar = {bar_x, L.image.y, kBarW * k, L.image.h};
    for (double v : ticks) {
        std::snprintf(buf, sizeof buf, "%g", v);
        const float ty = L.colorbar.y + float((c.hi_db - v) / span) * L.colorbar.h;
        L.colorbar_ticks.push_back(
            {buf, {bar_x + kBarW * k + kTickLen * k + 2 * k, ty - th / 2, t.width(buf), th}});
        L.colorbar_tick_db.push_back(v);
    }
    const float below = std::max(l.bounds.y + l.bounds.h, L.colorbar.y + L.colorbar.h + th / 2);
    L.ascan = {p.x + pad, below + pad, p.w - 2 * pad, p.y + p.h - pad - (below + pad)};
    return L;
}

} // namespace sonarsim::ui

// The sonar panel's plots and measurement: the colour bar, the A-scan, the ruler and region statistics, and
// the mapping between screen points and image places they share.
#include "ui/gl/sonar_panel.hpp"

#include "ui/model/image_views.hpp"
#include "core/display/polar_layout.hpp"
#include "ui/model/measure.hpp"
#include "ui/gl/sonar_panel_style.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <imgui.h>
#include <vector>

namespace sonarsim::ui {
using namespace panel;

std::optional<ImagePlace> SonarPanel::place_at(const Rect& r, const RenderResult& shown, ImVec2 q) const {
    const SonarParams& s = shown.scene.sonar;
    const Image8& fan = shown.frame->sector();
    const double u = (q.x - r.x) / r.w, v = (q.y - r.y) / r.h;
    if (polar) return polar_pixel_place(s, u * s.beams, v * s.range_bins);
    return sector_pixel_place(SectorLayout(shown.frame->grid_ptr, fan.height), s, u * fan.width,
                              v * fan.height);
}

ImVec2 SonarPanel::screen_of(const Rect& r, const RenderResult& shown, double range, double az) const {
    if (polar) {
        const PolarLayout PL(shown.frame->grid());
        return ImVec2(r.x + float(PL.u_of_azimuth_deg(az)) * r.w, r.y + float(PL.v_of_range_m(range)) * r.h);
    }
    const Image8& fan = shown.frame->sector();
    double px = 0, py = 0;
    SectorLayout(shown.frame->grid_ptr, fan.height).polar_to_pixel(range, az, px, py);
    return ImVec2(r.x + float(px / fan.width) * r.w, r.y + float(py / fan.height) * r.h);
}

void SonarPanel::draw_measure(const Rect& r, const RenderResult& shown) {
    if (!measure_a_ || !measure_b_) return;
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const ImagePlace &a = *measure_a_, &b = *measure_b_;
    // The region: range x azimuth between the two places (an annular sector in the fan), and the ruler.
    const int n = 24;
    std::vector<ImVec2> outline;
    for (int k = 0; k <= n; ++k)
        outline.push_back(
            screen_of(r, shown, a.range_m, a.azimuth_deg + (b.azimuth_deg - a.azimuth_deg) * k / n));
    for (int k = 0; k <= n; ++k)
        outline.push_back(
            screen_of(r, shown, b.range_m, b.azimuth_deg + (a.azimuth_deg - b.azimuth_deg) * k / n));
    const ImU32 c = IM_COL32(80, 255, 160, 255);
    dl->AddPolyline(outline.data(), int(outline.size()), c, ImDrawFlags_Closed, 1.0f);
    const ImVec2 pa = screen_of(r, shown, a.range_m, a.azimuth_deg),
                 pb = screen_of(r, shown, b.range_m, b.azimuth_deg);
    dl->AddLine(pa, pb, c, 2.0f);
    const RegionStats st = region_stats(shown.frame->polar(), shown.scene.sonar, a, b);
    char buf[200];
    if (st.echo_cells > 0)
        std::snprintf(buf, sizeof buf,
                      "distance %.3f m | %d cells, %d echo: mean %.1f  median %.1f  min %.1f  max %.1f dB",
                      image_distance_m(a, b), st.cells, st.echo_cells, st.mean_db, st.median_db, st.min_db,
                      st.max_db);
    else
        std::snprintf(buf, sizeof buf, "distance %.3f m | %d cells, no echo", image_distance_m(a, b),
                      st.cells);
    last_measure_ = buf;
}

void SonarPanel::draw_colorbar(const DisplayParams& d) {
    const Rect& r = layout_.colorbar;
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const int n = 48;
    for (int k = 0; k < n; ++k) {
        const auto c0 = colormap_rgb(d.colormap, 1.0 - double(k) / n);
        const auto c1 = colormap_rgb(d.colormap, 1.0 - double(k + 1) / n);
        dl->AddRectFilledMultiColor(ImVec2(r.x, r.y + r.h * k / n),
                                    ImVec2(r.x + r.w, r.y + r.h * (k + 1) / n),
                                    IM_COL32(c0[0], c0[1], c0[2], 255), IM_COL32(c0[0], c0[1], c0[2], 255),
                                    IM_COL32(c1[0], c1[1], c1[2], 255), IM_COL32(c1[0], c1[1], c1[2], 255));
    }
    dl->AddRect(ImVec2(r.x, r.y), ImVec2(r.x + r.w, r.y + r.h), IM_COL32(200, 200, 200, 120));
    for (const PanelLabel& t : layout_.colorbar_ticks) {
        const float y = t.box.y + t.box.h / 2;
        dl->AddLine(ImVec2(r.x + r.w, y), ImVec2(t.box.x - 2, y), kLabelColor);
        dl->AddText(ImVec2(t.box.x, t.box.y), kLabelColor, t.text.c_str());
    }
    const PanelLabel& title = layout_.colorbar_title;
    dl->PushClipRect(ImVec2(title.box.x, title.box.y),
                     ImVec2(title.box.x + title.box.w, title.box.y + title.box.h), true);
    dl->AddText(ImVec2(title.box.x, title.box.y), kLabelColor, title.text.c_str());
    dl->PopClipRect();
}

void SonarPanel::draw_ascan(const Rect& r, const RenderResult& shown) {
    const DisplayParams& d = shown.frame->display;
    const PolarImage& img = shown.frame->polar();
    if (ascan_beam_ >= 0 && ascan_beams_ != img.beams) {
        // The beam count changed: the beam nearest the azimuth it showed.
        ascan_beam_ = beam_at_azimuth(ascan_azimuth_deg_, shown.frame->grid());
        ascan_beams_ = img.beams;
    }
    if (ascan_beam_ < 0 || ascan_beam_ >= img.beams) {
        ascan_beam_ = strongest_beam(img), ascan_beams_ = img.beams;
        ascan_azimuth_deg_ = shown.frame->grid().beam_azimuth_deg(ascan_beam_);
    }
    const std::vector<float> lv = beam_levels(img, ascan_beam_);
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const double a = shown.frame->grid().beam_azimuth_deg(ascan_beam_);
    char buf[96];
    const char* level = shown.scene.sensor.model == SensorModel::Ideal ? "L_EN" : "device level";
    std::snprintf(buf, sizeof buf, "A-scan: beam %d (az %+.2f deg): %s [dB] vs range [m]", ascan_beam_, a,
                  level);
    if (ImGui::CalcTextSize(buf).x > r.w)
        std::snprintf(buf, sizeof buf, "A-scan beam %d (%+.1f deg) dB vs m", ascan_beam_, a);
    text_at(dl, ImVec2(r.x, r.y), kLabelColor, buf);
    const float lh = ImGui::GetTextLineHeight();
    const Rect p{r.x + 3.2f * lh, r.y + 1.4f * lh, r.w - 3.8f * lh, r.h - 2.8f * lh};
    dl->AddRectFilled(ImVec2(p.x, p.y), ImVec2(p.x + p.w, p.y + p.h), IM_COL32(16, 18, 24, 255));

    double lo = std::min(d.lo_db, d.hi_db) - 10, hi = std::max(d.lo_db, d.hi_db) + 10;
    for (float v : lv)
        if (std::isfinite(v)) lo = std::min(lo, double(v)), hi = std::max(hi, double(v));
    const double ystep = nice_step(hi - lo, 4);
    lo = std::floor(lo / ystep) * ystep, hi = std::ceil(hi / ystep) * ystep;
    const SonarGrid& grid = shown.frame->grid();
    const PolarLayout PL(grid);
    auto X = [&](double range) { return p.x + float(1 - PL.v_of_range_m(range)) * p.w; };
    auto Y = [&](double db) { return p.y + float((hi - db) / (hi - lo)) * p.h; };
    // Display window lo..hi as a band.
    dl->AddRectFilled(ImVec2(p.x, Y(std::max(d.lo_db, d.hi_db))),
                      ImVec2(p.x + p.w, Y(std::min(d.lo_db, d.hi_db))), IM_COL32(80, 90, 120, 60));
    for (double v = lo; v <= hi + 1e-9; v += ystep) {
        dl->AddLine(ImVec2(p.x, Y(v)), ImVec2(p.x + p.w, Y(v)), IM_COL32(255, 255, 255, 30));
        std::snprintf(buf, sizeof buf, "%g", v);
        text_at(dl, ImVec2(p.x - 4, Y(v)), kLabelColor, buf, 1.0f, 0.5f);
    }
    const double rstep = nice_step(grid.window_m(), 6);
    for (double rr = std::ceil(grid.range_min_m / rstep - 1e-9) * rstep; rr <= grid.range_max_m + 1e-9;
         rr += rstep) {
        dl->AddLine(ImVec2(X(rr), p.y), ImVec2(X(rr), p.y + p.h), IM_COL32(255, 255, 255, 30));
        std::snprintf(buf, sizeof buf, "%g", rr);
        text_at(dl, ImVec2(X(rr), p.y + p.h + 2), kLabelColor, buf, 0.5f, 0.0f);
    }
    // The curve, broken where nothing echoes.
    std::vector<ImVec2> run;
    auto flush = [&] {
        if (run.size() >= 2)
            dl->AddPolyline(run.data(), int(run.size()), IM_COL32(120, 220, 255, 255), 0, 1.5f);
        else if (run.size() == 1)
            dl->AddCircleFilled(run[0], 1.5f, IM_COL32(120, 220, 255, 255));
        run.clear();
    };
    dl->PushClipRect(ImVec2(p.x, p.y), ImVec2(p.x + p.w, p.y + p.h), true);
    for (size_t k = 0; k < lv.size(); ++k) {
        if (!std::isfinite(lv[k])) {
            flush();
            continue;
        }
        run.push_back(ImVec2(X(grid.bin_centre_m(int(k))), Y(lv[k])));
    }
    flush();
    if (hovered_)
        dl->AddLine(ImVec2(X(hovered_->range_m), p.y), ImVec2(X(hovered_->range_m), p.y + p.h), kHoverColor);
    dl->PopClipRect();
}

} // namespace sonarsim::ui

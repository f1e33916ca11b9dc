// The sonar image panel's layout, GL-free: where the hover readout, the image (fan or raw polar), its
// bearing and range labels, the colour bar with its ticks and title, and the A-scan go. The image is as large
// as the panel allows with every label outside it, none clipped and none overlapping another, the colour bar
// or the image; the rest of the height goes to the A-scan. ui/gl/sonar_panel.cpp draws what this places;
// `sonarsim view --layout` checks the text drawn against the image and the colour bar (text_layout.hpp).
#pragma once
#include "ui/model/layout.hpp"

#include "core/display/image.hpp"
#include "core/data/scene.hpp"
#include "core/grid/sonar_grid.hpp"

#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace sonarsim::ui {

/// Text size of the UI font (monospace: ImGui's default font is 7 x 13 px at scale 1).
struct TextMetrics {
    float char_w = 7, line_h = 13;
    float width(const std::string& s) const { return char_w * float(s.size()); }
};

struct PanelLabel {
    std::string text;
    Rect box; ///< where the text is drawn [window px]
};

/// The fan on screen: the sonar's apex, metres to pixels, the range window and the half field of view.
struct FanOnScreen {
    glm::dvec2 apex{0};
    double px_per_m = 1, r_min_m = 0, r_max_m = 1;
    /// The fan's port and starboard edges [deg] (SonarGrid: a beam table's fan need not be symmetric).
    double port_deg = 45, starboard_deg = -45;
    /// Screen point at range r [m] and azimuth a [deg] (port, positive azimuth, on the left).
    glm::dvec2 at(double range_m, double azimuth_deg) const;
    /// True inside the annular sector r_min..r_max x starboard..port.
    bool contains(double x, double y) const;
};

/// Readout lines reserved above the image (hover, echo path, ground truth over two lines).
constexpr int kReadoutLines = 4;

struct SonarPanelLayout {
    Rect readout;    ///< the hover / measurement / 3D point readout
    Rect image;      ///< the sector image (or the raw polar image)
    FanOnScreen fan; ///< the fan inside `image` (sector view)
    Rect colorbar;   ///< the bar itself
    PanelLabel colorbar_title;
    std::vector<PanelLabel> colorbar_ticks;
    std::vector<double> colorbar_tick_db;     ///< the level of each tick
    std::vector<PanelLabel> bearings, ranges; ///< outside the image, not overlapping
    std::vector<double> bearing_deg, range_m; ///< the angle / range of each label
    Rect ascan;
};

struct PanelContent {
    SonarParams sonar;
    double lo_db = 0, hi_db = 1; ///< the displayed range (colour bar ticks)
    std::string colorbar_title;  ///< what the colours are (colorbar_title())
    bool polar = false;          ///< the raw polar image instead of the fan
    int fan_height_px = 0;       ///< the fan image's height [px] (0: one row per range bin)
};

/// `panel`: the sonar panel [window px]; `scale`: the UI scale (paddings).
SonarPanelLayout sonar_panel_layout(const Rect& panel, const PanelContent& content, const TextMetrics& text,
                                    float scale = 1.0f);

/// The colour bar's title: "L_EN dB" for the ideal image, "level dB (TVG, gain)" for the device sensor's.
std::string colorbar_title(const SceneDesc& scene);

/// The fan height to form for a fan shown `shown_h_px` device pixels high (Simulator::set_fan_height_px):
/// that height rounded up to a multiple of 64, at least 256 (a resize does not re-form the fan at every
/// pixel), or 0 (one row per range bin) where that is no taller.
int fan_height_to_form(double shown_h_px, const SonarGrid& grid);

/// Width / height of the fan (the sector image) of these sonar settings.
double fan_aspect(const SonarParams& sonar);

/// Width [px] the sonar panel would like for a fan of aspect w/h in a window of this height: as wide as the
/// fan needs to fill the height left above the A-scan (viewer_layout caps it).
float sonar_panel_width_wanted(int window_h, double fan_w_over_h, float scale);

} // namespace sonarsim::ui

// The sonar image panel (ImGui): the aspect-correct fan (or the raw polar image) with range rings and bearing
// lines labelled in m and deg, a colour bar in dB, the A-scan of the hovered beam, and the pixel of a hovered
// 3D surface point.
#pragma once
#include "ui/model/echo_path_view.hpp"
#include "ui/gl/gl_util.hpp"
#include "ui/model/image_views.hpp"
#include "ui/model/layout.hpp"
#include "ui/model/panel_layout.hpp"
#include "ui/model/session.hpp"
#include "ui/model/sonar_geometry.hpp"

#include <cstdint>
#include <imgui.h>
#include <memory>
#include <optional>
#include <string>

namespace sonarsim::ui {

class SonarPanel {
  public:
    /// Draws the panel. `marker`: a world point (hovered in 3D) whose pixel is marked; `scale`: the UI scale.
    void draw(const Rect& area, Session& session, const std::optional<glm::dvec3>& marker, float scale = 1);
    /// The image place under the mouse this frame (none when the mouse is elsewhere).
    const std::optional<ImagePlace>& hovered() const { return hovered_; }
    /// The strongest echo path into the hovered cell, from the shown frame (invalid when none is hovered).
    const HoveredPath& hovered_path() const { return path_; }
    bool polar = false; ///< show the raw polar image instead of the fan
    /// Measuring (M): drag on the image from one place to another; Escape ends it.
    void start_measure() { measuring_ = true, measure_a_.reset(), measure_b_.reset(), last_measure_.clear(); }
    void cancel_measure() {
        measuring_ = false, measure_a_.reset(), measure_b_.reset(), last_measure_.clear();
    }
    const std::string& measurement() const { return last_measure_; }
    bool measuring() const { return measuring_; }
    /// What an annotated snapshot captures: the image with its labels and the colour bar [window px].
    const Rect& annotated_rect() const { return annotated_; }
    /// Where this frame placed the image, its labels and the colour bar (for the layout check).
    const SonarPanelLayout& layout() const { return layout_; }
    /// False until an image was drawn (layout() is then empty).
    bool has_layout() const { return has_layout_; }

  private:
    void draw_fan_overlay(const Rect& r, const RenderResult& shown);
    void draw_polar_overlay(const Rect& r, const RenderResult& shown);
    void draw_labels();
    void draw_colorbar(const DisplayParams& d);
    void draw_ascan(const Rect& r, const RenderResult& shown);
    void draw_header(const Session& session, Session& edit);
    /// A side-scan's waterfall or a scanning sonar's sweep, fitted to the area below the header, with what
    /// it shows in words.
    void draw_pings(const Rect& area, const RenderResult& shown, std::uint64_t shown_count);
    void ask_fan_height(const Rect& area, Session& session, float scale);
    /// The place at screen point q, or nullopt off the image.
    std::optional<ImagePlace> place_at(const Rect& r, const RenderResult& shown, ImVec2 q) const;
    ImVec2 screen_of(const Rect& r, const RenderResult& shown, double range_m, double azimuth_deg) const;
    void draw_measure(const Rect& r, const RenderResult& shown);

    gl::Texture texture_;
    std::uint64_t uploaded_count_ = 0;
    bool uploaded_polar_ = false;
    std::optional<ImagePlace> hovered_;
    HoveredPath path_;
    int ascan_beam_ = -1, ascan_beams_ = 0; ///< the A-scan's beam, and the beam count it was chosen at
    double ascan_azimuth_deg_ = 0;          ///< its azimuth: kept (nearest beam) when the count changes
    bool measuring_ = false;
    std::optional<ImagePlace> measure_a_, measure_b_;
    Rect annotated_;
    SonarPanelLayout layout_;
    bool has_layout_ = false;
    /// What the fan height last asked for (ask_fan_height) was laid out from, and that height.
    struct FanHeightAsked {
        Rect area;
        float scale = 1, framebuffer_scale = 1;
        TextMetrics text;
        std::shared_ptr<const SonarGrid> grid;
        double lo_db = 0, hi_db = 0;
        std::string title;
        int height_px = 0;
        bool same_as(const FanHeightAsked& other) const; ///< the same inputs (height_px aside)
    };
    std::optional<FanHeightAsked> asked_;
    std::string last_measure_; ///< the measurement's numbers, shown under the image
    float scale_ = 1;
};

} // namespace sonarsim::ui

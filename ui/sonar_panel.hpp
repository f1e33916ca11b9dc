// The sonar image panel (ImGui): the aspect-correct fan (or the raw polar image) with range rings and bearing
// lines labelled in m and deg, a colour bar in dB, the A-scan of the hovered beam, and the pixel of a hovered
// 3D surface point.
#pragma once
#include "gl_util.hpp"
#include "layout.hpp"
#include "session.hpp"
#include "sonar_geometry.hpp"

#include <cstdint>
#include <optional>

namespace sonarsim::ui {

class SonarPanel {
  public:
    /// Draws the panel. `marker`: a world point (hovered in 3D) whose pixel is marked.
    void draw(const Rect& area, Session& session, const std::optional<glm::dvec3>& marker);
    /// The image place under the mouse this frame (none when the mouse is elsewhere).
    const std::optional<ImagePlace>& hovered() const { return hovered_; }
    bool polar = false; ///< show the raw polar image instead of the fan

  private:
    void draw_fan_overlay(const Rect& r, const RenderResult& shown);
    void draw_polar_overlay(const Rect& r, const RenderResult& shown);
    void draw_colorbar(const Rect& r, const DisplayParams& d);
    void draw_ascan(const Rect& r, const RenderResult& shown);

    gl::Texture texture_;
    std::uint64_t uploaded_count_ = 0;
    bool uploaded_polar_ = false;
    std::optional<ImagePlace> hovered_;
    int ascan_beam_ = -1;
};

} // namespace sonarsim::ui

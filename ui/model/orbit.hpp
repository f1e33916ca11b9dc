// Non-GL helpers of `sonarsim view --orbit`: the sonar's path and the frame-time statistics it prints.
#pragma once
#include "core/data/scene.hpp"

#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace sonarsim::ui {

/// Moves the sonar on a horizontal circle around the point its boresight looks at (on the floor, or 40% of
/// its reach), turning with it so that it keeps looking at that point: every frame needs a retrace.
class Orbiter {
  public:
    explicit Orbiter(const SceneDesc& scene);
    /// The pose of frame `frame` (1.5 deg further round per frame); frame 0 is the scene's pose.
    Pose at(int frame) const;
    glm::dvec3 centre() const { return centre_; }

  private:
    Pose start_;
    glm::dvec3 centre_{0};
    double radius_ = 1, phi0_ = 0;
};

/// Frame and image times of a run.
struct FrameStats {
    std::vector<double> frame_ms, image_ms;
    bool preview = false; ///< the images were previews (--orbit-preview)
    /// Per image with an error estimate: its estimated median |dB| error and the screen's precision then
    /// (half a grey level of the display range it was shown with).
    std::vector<double> estimate_median_db, screen_median_db;
    double full_image_ms = -1; ///< after the run: the full-quality image of the last pose (-1: not timed)
    /// One JSON line {"frames":N,"frame_ms_mean":..,"frame_ms_p95":..,"image_ms_mean":..,"image_ms_p95":..,
    /// "images":"full"|"preview"} over the frames after the first `skip` (start-up: first trace, shader
    /// compiles), with "estimate_median_db_mean", "screen_median_db_mean" and "at_screen_precision" (the
    /// share of images estimated at or below it) when images carried estimates, and "full_image_ms" when
    /// timed.
    std::string json_line(size_t skip = 1) const;
};

} // namespace sonarsim::ui

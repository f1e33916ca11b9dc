// Snapshots of the viewer: the sonar files exactly as `sonarsim render` writes them, a PNG of the 3D view,
// and the scene file (current pose and parameters) that reproduces the raw image through `render --scene`.
#pragma once
#include "core/io/output.hpp"
#include "core/shading/ground_truth.hpp"
#include "core/pipeline/simulator.hpp"

#include <string>
#include <vector>

namespace sonarsim::ui {

/// "DIR/sonarsim_YYYYmmdd_HHMMSS" (local time); a "_N" suffix keeps it from overwriting an earlier snapshot.
std::string default_snapshot_prefix(const std::string& dir);

/// Writes PREFIX.png, PREFIX_polar.png, PREFIX.npy, PREFIX.json (as `render` does), PREFIX_3d.png (when
/// `view3d_png` is not empty), PREFIX_annotated.png (when `annotated_png` is not empty: the sonar panel as
/// drawn) and PREFIX_scene.json, all in one atomic step. Returns every path written.
std::vector<std::string> write_snapshot(const std::string& prefix, const SceneDesc& scene, const Frame& frame,
                                        const Bytes& view3d_png, const GroundTruth* ground_truth = nullptr,
                                        const Bytes& annotated_png = {});

/// The scene file text of a snapshot (JSON; round-trips through load_scene).
std::string snapshot_scene_text(const SceneDesc& scene);

/// The viewer's snapshots: those asked for (S taps, the menu), each taken once a full-quality image is on
/// screen, never of a drag's preview; and how many were written.
class SnapshotRequests {
  public:
    void ask() { ++pending_; }
    int pending() const { return pending_; }
    /// With the full-quality image on screen, calls `take()` once for each pending snapshot and returns
    /// true; with a preview on screen takes none and returns false (draw again, the full image comes).
    template <class Take> bool serve(bool full_on_screen, Take&& take) {
        if (pending_ == 0) return true;
        if (!full_on_screen) return false;
        for (; pending_ > 0; --pending_) take();
        return true;
    }
    void written() { ++written_; }
    int written_count() const { return written_; }

  private:
    int pending_ = 0, written_ = 0;
};

} // namespace sonarsim::ui

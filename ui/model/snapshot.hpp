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

} // namespace sonarsim::ui

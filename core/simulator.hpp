// The pipeline with per-stage invalidation: geometry -> trace -> shade -> display.
// A display change re-maps the image; physics re-shades the stored hits; pose or sampling re-traces;
// objects rebuild the Embree scene. Not thread-safe: give each worker thread its own Simulator.
#pragma once
#include "geometry.hpp"
#include "image.hpp"
#include "params.hpp"
#include "scene.hpp"
#include "shade.hpp"
#include "trace.hpp"

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace sonarsim {

struct Frame {
    TraceResult hits;
    PolarImage polar; ///< L_EN [dB]
    Image8 sector;    ///< RGB fan
    double alpha_db_per_m = 0;
    double trace_ms = 0, shade_ms = 0, image_ms = 0;
};

/// Earliest stage at which two scenes differ (Stage::None if they render identically). Under the adaptive
/// scheme, absorption (f, T, D) and material q, mu, h re-trace: they decide where its rays go.
Stage changed_stage(const SceneDesc& before, const SceneDesc& after);

class Simulator {
  public:
    explicit Simulator(const SceneDesc& scene);
    /// Replace the scene; only the stages it affects are recomputed on the next render().
    void set_scene(const SceneDesc& scene);
    const SceneDesc& scene() const { return scene_; }
    const SceneGeometry& geometry() const { return *geometry_; }
    /// Recomputes what is stale and returns the frame.
    const Frame& render();
    /// Stage that the next render() starts at.
    Stage pending() const { return dirty_; }

  private:
    SceneDesc scene_;
    std::unique_ptr<SceneGeometry> geometry_;
    Frame frame_;
    std::unique_ptr<SectorResampler> resampler_; ///< rebuilt only when the image geometry changes
    Stage dirty_ = Stage::Trace;
};

/// Metadata of a rendered frame: every effective parameter plus derived values and timings.
json frame_metadata(const SceneDesc& scene, const Frame& frame);

/// Writes PREFIX.png (sector), PREFIX_polar.png, PREFIX.npy and PREFIX.json atomically (what `render`
/// writes). `extra` files (e.g. a 3D view PNG or a scene file) are written in the same atomic step.
void write_render_files(const std::string& prefix, const SceneDesc& scene, const Frame& frame,
                        std::vector<std::pair<std::string, std::vector<std::uint8_t>>> extra = {});

} // namespace sonarsim

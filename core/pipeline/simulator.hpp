// The pipeline with per-stage invalidation: geometry -> trace -> shade -> sensor -> display.
// A display change re-maps the image; a sensor change (noise, speckle, gain...) re-runs the sensor stage on
// the shaded image; physics re-shades the stored hits; pose or sampling re-traces; objects rebuild the
// Embree scene. Not thread-safe: give each worker thread its own Simulator.
#pragma once
#include "core/geometry/geometry.hpp"
#include "core/display/image.hpp"
#include "core/scene/params.hpp"
#include "core/data/scene.hpp"
#include "core/shading/accumulate.hpp"
#include "core/sampling/trace.hpp"

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace sonarsim {

/// A finished image. Its stage results are immutable and shared, never copied: a later frame whose display
/// changed shares this one's trace and polar image, a re-shaded one shares its trace. Safe to read from any
/// thread while the Simulator renders the next frame.
struct Frame {
    std::shared_ptr<const SonarGrid> grid_ptr; ///< the sonar's beams, bins and fan layout
    std::shared_ptr<const TraceResult> hits_ptr;
    std::shared_ptr<const PolarImage> ideal_ptr;    ///< L_EN [dB] as the sampler converges it
    std::shared_ptr<const SensorInputs> inputs_ptr; ///< what the sensor needs beyond it (or null)
    std::shared_ptr<const PolarImage> polar_ptr;    ///< the sensor's output [dB]; ideal_ptr itself when ideal
    std::shared_ptr<const Image8> sector_ptr;       ///< RGB fan
    /// The fan's pixel -> (bin, beam) taps sector_ptr was formed with (kept while the geometry stays).
    std::shared_ptr<const SectorResampler> sector_map_ptr;
    std::shared_ptr<const GroundTruth> truth_ptr; ///< when asked for (Simulator::request), else null
    /// Per image cell the strongest contribution (for drawing its path), when asked for, else null.
    std::shared_ptr<const StrongestContribution> strongest_ptr;
    std::vector<double> path_order_db; ///< with multipath (sampling.bounces > 0): echo per path order [dB]
    DisplayParams display;             ///< the display range it is shown with (display.auto)
    /// The sampler's error estimate of the ideal image: the tracer's (adaptive), or, for hits in two
    /// halves (jittered), made from the hits with this frame's shading (estimate_error).
    TraceResult::ErrorEstimate error_estimate;
    double alpha_db_per_m = 0;
    /// Each stage's time in making this frame; 0 where the frame shares the stage's result with an earlier
    /// one.
    double trace_ms = 0, shade_ms = 0, sensor_ms = 0, image_ms = 0;

    const TraceResult& hits() const { return *hits_ptr; }
    const SonarGrid& grid() const { return *grid_ptr; }
    /// The image the device shows [dB]: L_EN through the sensor stage (with the ideal sensor, L_EN).
    const PolarImage& polar() const { return *polar_ptr; }
    const PolarImage& ideal() const { return *ideal_ptr; }
    bool sensor_applied() const { return polar_ptr != ideal_ptr; }
    const Image8& sector() const { return *sector_ptr; }
    /// The hits were placed by the adaptive sampler for an earlier scene: a preview re-shaded them after a
    /// `steers_sampler` value changed (Stage::Place). Its images are this scene's; its error estimate is not.
    bool placement_stale = false;
    /// Full quality, with hits placed by the adaptive sampler for an earlier shading of this scene
    /// (TraceControl::keep_placement): re-shaded, and its error estimate made anew with this shading
    /// (reestimate_error), which meets the tolerances or, where the trace itself stopped short of them, is
    /// within one tolerance of what it reached (kept_placement_serves). A fresh Simulator places its rays
    /// anew.
    bool placement_kept = false;
    /// A coarse preview (TraceControl::preview: the base grid, or hits placed for an earlier scene): never
    /// to be taken for the full-quality image.
    bool preview() const { return (hits_ptr && hits_ptr->preview) || placement_stale; }
};

/// What a frame carries beyond the images, each made in the shading pass only when asked for.
struct FrameExtras {
    bool ground_truth = false; ///< Frame::truth_ptr
    bool echo_paths = false;   ///< Frame::strongest_ptr
};

class Simulator {
  public:
    explicit Simulator(const SceneDesc& scene);
    /// Replace the scene; only the stages it affects are recomputed on the next render().
    void set_scene(const SceneDesc& scene);
    /// The same, with `changed` = changed_stage(scene(), scene) already known (or an earlier stage).
    void set_scene(const SceneDesc& scene, Stage changed);
    const SceneDesc& scene() const { return scene_; }
    const SceneGeometry& geometry() const { return *geometry_; }
    /// Recomputes what is stale and returns the frame, which shares the unchanged stages with earlier ones.
    /// `control.cancel` stops the trace within milliseconds: render() then throws TraceCancelled and the
    /// simulator is as before the call (its stale stages stay stale). `control.preview` (adaptive scheme)
    /// traces the base grid only, or, when only `steers_sampler` values changed (Stage::Place), re-shades the
    /// hits it has and traces nothing; the next render() without it re-traces, even if the scene is
    /// unchanged, so that a full-quality image is always the one a fresh Simulator makes, unless
    /// `control.keep_placement` keeps the hits whose estimate, made anew, still meets the tolerances.
    std::shared_ptr<const Frame> render(const TraceControl& control = {});
    /// The extras the next frames carry; asking for one the last frame lacks re-runs the shading pass for it
    /// alone on the next render() (the image stages are shared).
    void request(const FrameExtras& extras);
    /// Hand over hits traced earlier for this very scene as it is now (its geometry, pose and placement; a
    /// ping heard again from the same pose, render_pings): the next render() shades them and traces nothing,
    /// unless it is a full-quality render and they are a preview's (TraceResult::preview).
    void set_hits(std::shared_ptr<const TraceResult> hits);
    /// Stage that the next render() starts at.
    Stage pending() const { return dirty_; }
    /// Rays (multipath continuations included) traced by this simulator's renders so far.
    std::uint64_t rays_traced() const { return rays_traced_; }
    /// Height of the fan (Frame::sector) the display stage forms [px]; 0 (the default): the grid's
    /// default_fan_height_px, one row per range bin. A viewer shows the fan a few hundred pixels high and
    /// asks for that: a 512 x 2048 fan is 3721 x 2048 px, its map 160 ms to build. A change re-forms the fan
    /// only.
    void set_fan_height_px(int height_px);
    /// Whether render() forms the fan (Frame::sector; the default): a side-scan's or scan's ping, a one-beam
    /// image, needs only its levels.
    void set_forms_fan(bool forms_fan);
    /// The display range the last frame was shown with (display.auto: the one chosen from its image); the
    /// scene's before the first.
    const DisplayParams& display() const { return frame_.polar_ptr ? frame_.display : scene_.display; }
    /// Elevation strata per beam of the next screen-precision preview (TraceControl::preview_median_db).
    int preview_strata() const { return preview_strata_; }

  private:
    /// A preview at TraceControl::preview_median_db: a jittered grid of preview_strata_ strata per beam.
    TraceResult trace_screen_preview(const TraceControl& control);
    /// Sizes the next screen-precision preview from this one's estimate and time.
    void resize_preview(const TraceResult::ErrorEstimate& estimate, double target_db, double took_ms,
                        double budget_ms);
    SceneDesc scene_;
    std::unique_ptr<SceneGeometry> geometry_;
    Frame frame_;
    std::shared_ptr<const SectorResampler> resampler_; ///< rebuilt only when the image geometry changes
    Stage dirty_ = Stage::Trace;
    FrameExtras extras_;
    std::uint64_t rays_traced_ = 0;
    int fan_height_px_ = 0;
    bool forms_fan_ = true;
    int preview_strata_ = 32;
};

/// Metadata of a rendered frame: every effective parameter plus derived values and timings.
json frame_metadata(const SceneDesc& scene, const Frame& frame);

} // namespace sonarsim

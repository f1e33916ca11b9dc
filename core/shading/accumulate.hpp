// The accumulation pass: every cell's echo is evaluated once per (re)shade, and one walk over the cells and
// the range bins each one's footprint covers fills every channel a frame needs. Channels nobody asked for
// cost nothing.
#pragma once
#include "core/data/polar_image.hpp"
#include "core/data/hits.hpp"
#include "core/data/channels.hpp"
#include "core/data/scene.hpp"
#include "core/shading/ground_truth.hpp"

#include <cstdint>
#include <memory>
#include <vector>

namespace sonarsim {

/// What the sensor stage needs from the cells beyond the image (computed only when it needs it).
struct SensorInputs {
    int sub = 1;     ///< fine azimuth columns per beam (column j = beam * sub + s, s = 0 port-most)
    PolarImage fine; ///< L_EN [dB] per (range bin, fine column) when sub > 1; otherwise empty
    /// Per (range bin, beam) [bin * beams + beam]: the echo-weighted mean elevation [rad] of what echoes
    /// there (each cell at the elevation where its footprint crosses the bin's centre range); NaN where
    /// nothing echoes. Empty unless speckle is on (it anchors the speckle to the scatterers).
    std::vector<float> elevation_rad;
};

/// True when the sensor needs SensorInputs: a receive pattern finer than the beams, or speckle.
bool needs_sensor_inputs(const SceneDesc& scene);

/// Per (range bin, beam) [bin * beams + beam] the index of the strongest contribution to that cell among
/// the beam's contributions (BeamContributions order: cells, then ghosts); -1 where nothing echoes.
struct StrongestContribution {
    int bins = 0, beams = 0;
    std::vector<std::int32_t> index;
    std::int32_t at(int bin, int beam) const { return index[size_t(bin) * size_t(beams) + size_t(beam)]; }
};

/// What one pass produced; a channel not asked for is null (or empty).
struct Accumulation {
    std::shared_ptr<const PolarImage> image;
    std::shared_ptr<const SensorInputs> inputs;
    std::shared_ptr<const GroundTruth> truth;
    std::shared_ptr<const StrongestContribution> strongest;
    /// Echo [dB, as the image's L_EN + L_N summed over bins inside the window] per path order (reflections,
    /// out and back: 0 direct ... 2 x sampling.bounces); -inf for an order with no echo. Empty unless asked.
    std::vector<double> path_order_db;
};

/// One pass over the stored hits. Per beam: each contribution's level (contribution_levels), weights
/// relative to the beam's strongest (one exp per contribution), then one walk over the range bins of each
/// contribution's footprint feeding every asked-for channel. Intensities far below double's range are summed
/// in the log domain instead (image: a beam with a bin more than ~3000 dB below its peak).
Accumulation accumulate(const TraceResult& hits, const SceneDesc& scene, const Channels& channels);

/// The accumulation pass of a whole image, owned by its caller. A tracer whose placement reads the shaded
/// image (adaptive) runs the pass through the one it is given, so the caller takes the pass of the hits
/// returned instead of running it again: no cell's echo is evaluated twice.
class ImagePass {
  public:
    /// The channels the caller will take (the image among them).
    explicit ImagePass(const Channels& channels = {}) : channels_(channels) { channels_.image = true; }
    /// Runs the pass on `hits` with the scene's grid and physics and keeps it as the latest.
    const Accumulation& run(const TraceResult& hits, const SceneDesc& scene);
    /// The hits changed since the latest pass: it is not theirs any more.
    void forget() { latest_.reset(); }
    /// The latest pass, of the hits as they were last handed back (null: none, run accumulate()).
    std::shared_ptr<const Accumulation> take() { return std::move(latest_); }

  private:
    Channels channels_;
    std::shared_ptr<const Accumulation> latest_;
};

/// The L_EN image of the stored hits alone: accumulate() with the image channel.
PolarImage shade(const TraceResult& hits, const SceneDesc& scene);

/// The L_EN image of some of the scene's beams as an image of their own: `columns` columns, column k hits'
/// beam k (e.g. the sample beams of an error estimate), shaded with the scene's physics and range bins. A
/// beam's image does not depend on the others, and the image needs no beam angles.
PolarImage shade_columns(const TraceResult& hits, const SceneDesc& scene, int columns);

} // namespace sonarsim

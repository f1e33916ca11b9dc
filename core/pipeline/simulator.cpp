#include "core/pipeline/simulator.hpp"

#include "core/data/pose.hpp"
#include "core/base/errors.hpp"
#include "core/base/scratch_pool.hpp"
#include "core/scene/device_overrides.hpp"
#include "core/scene/devices.hpp"
#include "core/sampling/acquisition.hpp"
#include "core/scene/sampling_scheme.hpp"
#include "core/scene/scene_io.hpp"
#include "core/shading/physics.hpp"
#include "core/sensor/sensor.hpp"
#include "core/shading/estimate.hpp"
#include "core/shading/shade.hpp"

#include <algorithm>
#include "core/base/timing.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>

namespace sonarsim {
namespace {

/// The staged simulator forms an imaging sonar's fan; the other kinds' pings are traced by render_pings.
const SceneDesc& imaging(const SceneDesc& scene) {
    if (scene.sonar.kind != SonarKind::Imaging)
        throw InputError(
            scene.source_file, "sonar.kind",
            "\"" + kind_name(scene.sonar.kind) +
                "\" is rendered ping by ping (sonarsim render, Python's render_pings); the viewer, "
                "batch and study take sonar.kind imaging");
    return scene;
}

} // namespace

Simulator::Simulator(const SceneDesc& scene)
    : scene_(imaging(scene)), geometry_(std::make_unique<SceneGeometry>(scene)) {}

void Simulator::set_scene(const SceneDesc& scene) {
    set_scene(scene, changed_stage(scene_, scene));
}

void Simulator::set_scene(const SceneDesc& scene, Stage s) {
    imaging(scene); // before anything changes
    // Objects only moved, turned or scaled: new instance transforms, no mesh read and no BVH rebuilt.
    // Otherwise a new geometry from the mesh cache. Either may throw, keeping the old geometry.
    if (s == Stage::Geometry && !geometry_->update_transforms(scene))
        geometry_ = std::make_unique<SceneGeometry>(scene);
    scene_ = scene;
    dirty_ = std::min(dirty_, s == Stage::Geometry ? Stage::Trace : s);
}

void Simulator::set_hits(std::shared_ptr<const TraceResult> hits) {
    if (!hits) throw std::invalid_argument("Simulator::set_hits: no hits");
    frame_.hits_ptr = std::move(hits);
    frame_.placement_stale = false, frame_.placement_kept = false;
    frame_.error_estimate = frame_.hits_ptr->error_estimate;
    dirty_ = Stage::Shade; // every stage from shading on is made anew from these hits
}

void Simulator::set_fan_height_px(int height_px) {
    if (height_px < 0)
        throw std::invalid_argument("Simulator: a fan height is 0 (the default) or more pixels");
    if (height_px != fan_height_px_) dirty_ = std::min(dirty_, Stage::Display);
    fan_height_px_ = height_px;
}

void Simulator::set_forms_fan(bool forms_fan) {
    if (forms_fan && !forms_fan_) dirty_ = std::min(dirty_, Stage::Display);
    forms_fan_ = forms_fan;
}

void Simulator::request(const FrameExtras& extras) {
    extras_ = extras;
}

namespace {

std::shared_ptr<const Image8> recycled_fan(const SectorResampler& resampler, const PolarImage& polar,
                                           const DisplayParams& display) {
    // Each frame's fan in a buffer an earlier frame gave back: a 512 x 2048 fan is 23 MB, and fresh pages
    // cost a fault and a clear each (about 20 ms of a 45 ms display stage, measured).
    auto fan = std::make_unique<Image8>();
    fan->pixels = scratch::take<std::uint8_t>(size_t(resampler.layout().width()) *
                                              size_t(resampler.layout().height()) * 3);
    resampler.apply_into(polar, display, *fan);
    return std::shared_ptr<const Image8>(fan.release(), [](const Image8* p) {
        std::unique_ptr<Image8> own(const_cast<Image8*>(p)); // made non-const above
        scratch::give(std::move(own->pixels));
    });
}

/// The sensor's image, its levels given back to the scratch pool when the last frame holding it goes (they
/// came from there: apply_sensor), so that the next image writes into pages already mapped.
std::shared_ptr<const PolarImage> recycled_polar(PolarImage&& image) {
    return std::shared_ptr<const PolarImage>(new PolarImage(std::move(image)), [](const PolarImage* p) {
        std::unique_ptr<PolarImage> own(const_cast<PolarImage*>(p)); // made non-const above
        scratch::give(std::move(own->level_db));
    });
}

} // namespace

namespace {

/// Rays a screen-precision preview takes at most (four per stratum): about 60 ms on two cores.
constexpr double kPreviewRays = 262144;
constexpr int kMinPreviewStrata = 8;

/// The most strata a preview of `beams` beams takes.
int most_preview_strata(int beams) {
    return std::max(kMinPreviewStrata, int(kPreviewRays / (4.0 * std::max(1, beams))));
}

/// Whether `control` asks for a preview at the screen's precision that `scene` can have (the adaptive
/// scheme with the footprints and true normals a jittered grid needs).
bool screen_preview(const SceneDesc& s, const TraceControl& control) {
    return control.preview && control.preview_median_db > 0 &&
           s.sampling.placement == RayPlacement::Adaptive && s.sampling.binning == EchoBinning::Footprint &&
           s.sampling.normals == NormalSource::Mesh;
}

} // namespace

TraceResult Simulator::trace_screen_preview(const TraceControl& control) {
    SceneDesc s = scene_;
    set_scheme(s.sampling, SamplingScheme::Jittered);
    // Sized for an earlier scene, perhaps of fewer beams: within this one's cap.
    preview_strata_ = std::min(preview_strata_, most_preview_strata(s.sonar.beams));
    s.sampling.elevation_rays = preview_strata_, s.sampling.azimuth_rays = 1;
    TraceResult t = trace(*geometry_, s, control);
    t.preview = true;
    return t;
}

void Simulator::resize_preview(const TraceResult::ErrorEstimate& e, double target_db, double took_ms,
                               double budget_ms) {
    // The jittered grid's median error falls about as 1 / strata (the wreck: 0.43, 0.19, 0.084 dB at 12, 24,
    // 48): a grid that missed the target, or met it with more than half to spare, is resized to reach 0.9 of
    // it, but no larger than the time a preview may take allows (its estimate then says what it reaches).
    const double most = most_preview_strata(scene_.sonar.beams);
    double want = preview_strata_;
    if (e.valid && e.median_abs_db > 0) {
        const double ratio = e.median_abs_db / target_db;
        if (ratio > 1 || ratio < 0.5) want = std::ceil(preview_strata_ * ratio / 0.9);
    }
    if (budget_ms > 0 && took_ms > 0) // time ~ strata
        want = std::min(want, preview_strata_ * budget_ms / took_ms);
    preview_strata_ = int(std::clamp(want, double(kMinPreviewStrata), most)); // NaN-free: e and times finite
}

std::shared_ptr<const Frame> Simulator::render(const TraceControl& control) {
    // frame_ holds the newest stage results; a stage recomputed here gets a new object, the others are
    // shared.
    Frame next = frame_;
    next.grid_ptr = sonar_grid(scene_.sonar); // the same object while the sonar's geometry stays
    next.trace_ms = next.shade_ms = next.sensor_ms = next.image_ms = 0; // this frame's work only
    // A full-quality image never keeps a preview's hits, nor hits placed for an earlier scene's shading
    // unless asked to keep them (TraceControl::keep_placement) and they carry what their estimate needs.
    const bool steered = dirty_ == Stage::Place || next.placement_stale;
    bool keeps = control.keep_placement && !control.preview && steered && dirty_ >= Stage::Place &&
                 next.hits_ptr && !next.hits_ptr->preview && next.hits_ptr->estimate_cells;
    TraceResult::ErrorEstimate kept_estimate; // the kept placement's estimate with this scene's shading
    double estimate_ms = 0;
    if (keeps) {
        // Kept while it serves (kept_placement_serves). The shown image is this scene's shading when only
        // later stages are stale.
        const auto t0 = std::chrono::steady_clock::now();
        kept_estimate = reestimate_error(
            *next.hits_ptr, scene_, dirty_ > Stage::Shade && next.ideal_ptr ? next.ideal_ptr.get() : nullptr);
        estimate_ms = ms_since(t0);
        keeps = kept_placement_serves(kept_estimate, next.hits_ptr->error_estimate, scene_.sampling);
    }
    const bool placed_before =
        next.preview() || dirty_ == Stage::Place || (next.placement_kept && !control.keep_placement);
    const bool retrace =
        dirty_ <= Stage::Trace || !next.hits_ptr || (placed_before && !control.preview && !keeps);
    const Stage from = retrace ? Stage::Trace : std::max(dirty_, Stage::Shade);
    const bool at_screen = retrace && screen_preview(scene_, control);
    // One accumulation pass: every channel this frame needs that is not shared with the frame before.
    const bool reshade = from <= Stage::Shade;
    Channels c;
    c.image = reshade;
    c.sensor_inputs = reshade && needs_sensor_inputs(scene_);
    c.path_orders = reshade && scene_.sampling.bounces > 0;
    c.ground_truth = extras_.ground_truth && (reshade || !next.truth_ptr);
    c.strongest = extras_.echo_paths && (reshade || !next.strongest_ptr);
    if (reshade) next.truth_ptr.reset(), next.strongest_ptr.reset(), next.path_order_db.clear();
    std::shared_ptr<const Accumulation> pass;
    if (retrace) {
        // The adaptive tracer shades to place its rays: through the pass this frame needs, which it may
        // then hand back for its hits. TraceCancelled: nothing has changed yet.
        ImagePass whole(c);
        TraceResult t =
            at_screen ? trace_screen_preview(control) : trace(*geometry_, scene_, control, &whole);
        next.trace_ms = t.trace_ms;
        next.placement_stale = false;
        rays_traced_ += t.rays_traced + t.multipath_rays;
        pass = whole.take(); // null unless the tracer ran the pass on its hits as returned
        next.hits_ptr = std::make_shared<const TraceResult>(std::move(t));
        next.error_estimate = next.hits_ptr->error_estimate;
    }
    if (!retrace && dirty_ == Stage::Place && !keeps) // a preview's re-shade
        next.placement_stale = true, next.placement_kept = false;
    if (!pass && c.any()) {
        const auto t0 = std::chrono::steady_clock::now();
        pass = std::make_shared<const Accumulation>(accumulate(*next.hits_ptr, scene_, c));
        next.shade_ms = ms_since(t0);
    } // else the tracer ran this frame's pass (its time is in trace_ms), or shared
    if (pass) {
        if (c.image) next.ideal_ptr = pass->image;
        if (reshade) next.inputs_ptr = pass->inputs;
        if (c.ground_truth) next.truth_ptr = pass->truth;
        if (c.strongest) next.strongest_ptr = pass->strongest;
        if (c.path_orders) next.path_order_db = pass->path_order_db;
    }
    if (reshade) next.alpha_db_per_m = shade_constants(scene_).alpha_db_per_m;
    if (reshade && next.hits_ptr->halves) { // jittered: the estimate from the hits, with this shading
        const auto t0 = std::chrono::steady_clock::now();
        next.error_estimate = estimate_error(*next.hits_ptr, scene_);
        next.shade_ms += ms_since(t0);
    }
    if (keeps) {
        next.error_estimate = kept_estimate;
        next.shade_ms += estimate_ms;
        next.placement_stale = false, next.placement_kept = true;
    }
    if (retrace) next.placement_kept = false;
    if (retrace && at_screen)
        resize_preview(next.error_estimate, control.preview_median_db, next.trace_ms + next.shade_ms,
                       control.preview_budget_ms);
    if (from <= Stage::Sensor) {
        const auto t0 = std::chrono::steady_clock::now();
        next.polar_ptr = sensor_is_ideal(scene_)
                             ? next.ideal_ptr
                             : recycled_polar(apply_sensor(*next.ideal_ptr, next.inputs_ptr.get(), scene_,
                                                           next.alpha_db_per_m));
        next.sensor_ms = ms_since(t0);
    }
    if (from <= Stage::Display && forms_fan_) {
        const auto t0 = std::chrono::steady_clock::now();
        if (!resampler_ || !resampler_->matches(*next.grid_ptr, fan_height_px_))
            resampler_ = std::make_shared<const SectorResampler>(next.grid_ptr, fan_height_px_);
        next.display = effective_display(*next.polar_ptr, scene_.display, *next.grid_ptr);
        next.sector_ptr = recycled_fan(*resampler_, *next.polar_ptr, next.display);
        next.sector_map_ptr = resampler_;
        next.image_ms = ms_since(t0);
    }
    frame_ = std::move(next);
    dirty_ = Stage::None;
    return std::make_shared<const Frame>(frame_); // a few pointers: the stages themselves are shared
}

json frame_metadata(const SceneDesc& s, const Frame& f) {
    json j = scene_to_json(s);
    j["alpha_db_per_m"] = f.alpha_db_per_m;
    j["sound_speed_m_s"] = sound_speed_m_s(s.water.temperature_c, s.water.depth_m);
    const auto grid = f.grid_ptr ? f.grid_ptr : sonar_grid(s.sonar);
    j["beam_azimuths_deg"] = grid->beam_azimuths_deg();
    j["range_bin_edges_m"] = grid->bin_edges_m();
    j["rays_traced"] = f.hits().rays_traced;
    if (s.sampling.bounces > 0) { // multipath: its extra rays, and the echo of each path order
        size_t ghosts = 0;
        for (auto& g : f.hits().ghosts) ghosts += g.size();
        json orders = json::array();
        for (double e : f.path_order_db) orders.push_back(std::isfinite(e) ? json(e) : json(nullptr));
        j["multipath"] = {
            {"rays", f.hits().multipath_rays},
            {"ghost_cells", ghosts},
            {"echo_db_by_order", orders},
            {"orders", "reflections out and back: 0 direct, then 1 ... 2 x bounces; null: none"}};
    }
    if (moving(s.sonar)) { // motion during the frame: how it was acquired
        const double c = sound_speed_m_s(s.water.temperature_c, s.water.depth_m);
        const auto slots = acquisition_slots(s.sonar, c);
        const auto change = slab_pose_change(s.sonar, c);
        j["motion"] = {{"pings", s.sonar.pings_per_frame},
                       {"ping_interval_s", ping_interval_s(s.sonar, c)},
                       {"slots", slots.size()},
                       {"frame_duration_s", slots.back().t_tx_s + 2 * s.sonar.range_max_m / c},
                       {"max_rotation_within_slot_deg", change.rotation_deg},
                       {"max_translation_within_slot_m", change.translation_m},
                       {"model",
                        "each (ping, range slab) traced from the pose at its receive time; range = half the "
                        "two-way path from the transmit position"}};
    }
    const auto& est = f.error_estimate;
    json estimate = nullptr;
    if (est.valid) {
        estimate = {{"rel_l1", est.rel_l1},
                    {"median_abs_db", est.median_abs_db},
                    {"p95_abs_db", est.p95_abs_db},
                    {"tolerance_met", est.meets(s.sampling)}};
        if (f.hits().halves) { // jittered
            estimate["variance_rel_l1"] = est.variance_rel_l1;
            estimate["footprint_rel_l1"] = est.footprint_rel_l1;
            estimate["method"] = "per bin on every few beams: half the difference of the two independent "
                                 "halves (variance_rel_l1) and a third of the change when each ray's cell is "
                                 "its whole stratum instead of its half (footprint_rel_l1, second order), "
                                 "added in quadrature";
        } else { // adaptive
            if (f.placement_kept)
                estimate["placement"] =
                    "kept: placed for an earlier shading of this scene (a viewer's slider), re-shaded; "
                    "this estimate made anew from the same cells with this shading (kept where it meets the "
                    "tolerances or, where the trace itself stopped short of them, is within one tolerance of "
                    "what the trace reached); a fresh render places its rays anew";
            estimate["passes"] = est.passes;
            estimate["budget_reached"] = est.budget_reached;
            estimate["max_rays"] = s.sampling.max_rays;
            estimate["azimuth_rel_l1"] = est.azimuth_rel_l1;
            estimate["method"] =
                std::string(
                    "the difference to the same cells one refinement level coarser (bins echoing in "
                    "both), half of it where merged cells straddle an edge and an eighth on one smooth "
                    "surface, plus an azimuth probe (three ray columns against one); ") +
                (est.strict ? "strict: refined in azimuth where the probe finds the larger share"
                            : "fast: the probe's share is reported (azimuth_rel_l1, included in rel_l1), not "
                              "refined; sampling.estimate strict refines it");
            // What it cannot see, said where the number is read (docs/accuracy-and-speed.md measures it).
            estimate["not_seen"] =
                est.strict ? "the azimuth probe samples every third cell of a sampled beam's columns"
                           : "the azimuth probe samples every ninth cell of a sampled beam's columns";
        }
    }
    j["sampling_error_estimate"] = estimate;
    j["time_ms"] = {{"trace", f.trace_ms},
                    {"shade", f.shade_ms},
                    {"sensor", f.sensor_ms},
                    {"image", f.image_ms},
                    {"total", f.trace_ms + f.shade_ms + f.sensor_ms + f.image_ms}};
    j["display_range_db"] = {f.display.lo_db, f.display.hi_db};
    if (find_device(s.sonar.device)) // the preset's keys the scene file or --set gave other values
        j["device_overrides"] = device_overrides_json(device_overrides(s));
    j["image"] = {{"npy_shape", {s.sonar.range_bins, s.sonar.beams}},
                  {"npy_rows", "range bins, row 0 nearest"},
                  {"npy_columns", "beams, column 0 port-most"},
                  {"npy_units", f.sensor_applied()
                                    ? "the sensor's output level dB (L_EN through the sensor stage, plus TVG "
                                      "and gain); -inf where nothing echoes. PREFIX_ideal.npy: L_EN dB"
                                    : "L_EN dB; -inf where nothing echoes"}};
    return j;
}

} // namespace sonarsim

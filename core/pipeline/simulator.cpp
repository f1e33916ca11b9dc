#include "core/pipeline/simulator.hpp"

#include "core/io/output.hpp"
#include "core/base/pose.hpp"
#include "core/scene/scene_io.hpp"
#include "core/sensor/sensor.hpp"
#include "core/shading/shade.hpp"

#include <algorithm>
#include "core/base/timing.hpp"

#include <chrono>
#include <cmath>

namespace sonarsim {
namespace {} // namespace

Stage changed_stage(const SceneDesc& a, const SceneDesc& b) {
    Stage st = Stage::None;
    auto mark = [&](Stage s) { st = std::min(st, s); };
    // Adaptive placement puts its rays where the echo level varies, so the parameters that change how it
    // varies over a surface or between materials (absorption, nu, q, the specular lobe) re-trace; pure
    // level offsets of the whole image (L_S, L_N) and display settings still only re-shade or re-map.
    const bool adaptive = b.sampling.placement == RayPlacement::Adaptive;
    const Stage shaping = adaptive ? Stage::Trace : Stage::Shade;
    for (auto& p : scene_params())
        if (p.get(a) != p.get(b))
            mark(p.key == "sonar.frequency_khz" || p.key == "water.temperature_c" ||
                         p.key == "water.depth_m" || p.key == "water.surface_roughness_m"
                     ? shaping
                     : p.stage);
    auto material_stage = [&](const Material& x, const Material& y) {
        if (x.q != y.q || x.mu != y.mu || x.h_deg != y.h_deg) mark(shaping);
        // nu sets a material's level against the others', which decides where the adaptive sampler's
        // refinement is worth its rays.
        if (x.nu_db != y.nu_db) mark(shaping);
        // A mirror appearing or going changes the traced paths; its loss, the ghosts' levels.
        if (x.is_mirror() != y.is_mirror()) mark(Stage::Trace);
        if (x.is_mirror() && x.reflection_db != y.reflection_db) mark(shaping);
    };
    material_stage(a.water.surface_material, b.water.surface_material);
    if (a.objects.size() != b.objects.size()) {
        mark(Stage::Geometry);
    } else {
        for (size_t i = 0; i < a.objects.size(); ++i) {
            const ObjectDesc &x = a.objects[i], &y = b.objects[i];
            if (x.mesh_resolved != y.mesh_resolved || x.box_m != y.box_m || x.position_m != y.position_m ||
                x.orientation_deg != y.orientation_deg || x.scale != y.scale)
                mark(Stage::Geometry);
            material_stage(x.material, y.material);
        }
    }
    if (bool(a.seafloor) != bool(b.seafloor))
        mark(Stage::Trace);
    else if (a.seafloor) {
        if (a.seafloor->height_m != b.seafloor->height_m) mark(Stage::Trace);
        material_stage(a.seafloor->material, b.seafloor->material);
    }
    return st;
}

Simulator::Simulator(const SceneDesc& scene)
    : scene_(scene), geometry_(std::make_unique<SceneGeometry>(scene)) {}

void Simulator::set_scene(const SceneDesc& scene) {
    const Stage s = changed_stage(scene_, scene);
    // Objects only moved, turned or scaled: new instance transforms, no mesh read and no BVH rebuilt.
    // Otherwise a new geometry from the mesh cache. Either may throw, keeping the old geometry.
    if (s == Stage::Geometry && !geometry_->update_transforms(scene))
        geometry_ = std::make_unique<SceneGeometry>(scene);
    scene_ = scene;
    dirty_ = std::min(dirty_, s == Stage::Geometry ? Stage::Trace : s);
}

std::shared_ptr<const Frame> Simulator::render(const TraceControl& control) {
    // frame_ holds the newest stage results; a stage recomputed here gets a new object, the others are
    // shared.
    Frame next = frame_;
    const bool retrace = dirty_ <= Stage::Trace || !next.hits_ptr || (next.preview() && !control.preview);
    const Stage from = retrace ? Stage::Trace : dirty_;
    bool shaded = false;
    if (retrace) {
        TraceResult t = trace(*geometry_, scene_, control); // TraceCancelled: nothing has changed yet
        next.trace_ms = t.trace_ms;
        if (t.shaded) { // the tracer shaded its cells with this very scene
            next.ideal_ptr = std::make_shared<const PolarImage>(std::move(*t.shaded));
            t.shaded.reset();
            next.alpha_db_per_m = shade_constants(scene_).alpha_db_per_m;
            next.shade_ms = 0;
            shaded = true;
        }
        next.hits_ptr = std::make_shared<const TraceResult>(std::move(t));
    }
    if (from <= Stage::Shade) {
        const auto t0 = std::chrono::steady_clock::now();
        if (!shaded) {
            next.ideal_ptr = std::make_shared<const PolarImage>(shade(*next.hits_ptr, scene_));
            next.alpha_db_per_m = shade_constants(scene_).alpha_db_per_m;
        }
        next.inputs_ptr =
            needs_sensor_inputs(scene_)
                ? std::make_shared<const SensorInputs>(shade_sensor_inputs(*next.hits_ptr, scene_))
                : nullptr;
        next.shade_ms = shaded && !next.inputs_ptr ? 0 : ms_since(t0);
    }
    if (from <= Stage::Sensor) {
        const auto t0 = std::chrono::steady_clock::now();
        next.polar_ptr = sensor_is_ideal(scene_)
                             ? next.ideal_ptr
                             : std::make_shared<const PolarImage>(apply_sensor(
                                   *next.ideal_ptr, next.inputs_ptr.get(), scene_, next.alpha_db_per_m));
        next.sensor_ms = ms_since(t0);
    }
    if (from <= Stage::Display) {
        const auto t0 = std::chrono::steady_clock::now();
        if (!resampler_ || !resampler_->matches(scene_.sonar, 0))
            resampler_ = std::make_unique<SectorResampler>(scene_.sonar, 0);
        next.display = effective_display(*next.polar_ptr, scene_.display, scene_.sonar);
        next.sector_ptr = std::make_shared<const Image8>(resampler_->apply(*next.polar_ptr, next.display));
        next.image_ms = ms_since(t0);
    }
    frame_ = std::move(next);
    dirty_ = Stage::None;
    return std::make_shared<const Frame>(frame_); // a few pointers: the stages themselves are shared
}

json frame_metadata(const SceneDesc& s, const Frame& f) {
    json j = scene_to_json(s);
    j["alpha_db_per_m"] = f.alpha_db_per_m;
    j["beam_azimuths_deg"] = beam_azimuths_deg(s.sonar);
    j["range_bin_edges_m"] = range_bin_edges_m(s.sonar);
    j["rays_traced"] = f.hits().rays_traced;
    if (s.sampling.bounces > 0) { // multipath: its extra rays, and the echo of each path order
        size_t ghosts = 0;
        for (auto& g : f.hits().ghosts) ghosts += g.size();
        json orders = json::array();
        for (double e : path_order_energy_db(f.hits(), s))
            orders.push_back(std::isfinite(e) ? json(e) : json(nullptr));
        j["multipath"] = {
            {"rays", f.hits().multipath_rays},
            {"ghost_cells", ghosts},
            {"echo_db_by_order", orders},
            {"orders", "reflections out and back: 0 direct, then 1 ... 2 x bounces; null: none"}};
    }
    const auto& est = f.hits().error_estimate;
    if (est.valid)
        j["sampling_error_estimate"] = {
            {"rel_l1", est.rel_l1},
            {"median_abs_db", est.median_abs_db},
            {"p95_abs_db", est.p95_abs_db},
            {"passes", est.passes},
            {"budget_reached", est.budget_reached},
            {"max_rays", s.sampling.max_rays},
            {"tolerance_met", est.median_abs_db <= s.sampling.tolerance_db},
            {"method",
             "half the difference to the same cells one refinement level coarser (bins echoing in both)"}};
    else
        j["sampling_error_estimate"] = nullptr;
    j["time_ms"] = {{"trace", f.trace_ms},
                    {"shade", f.shade_ms},
                    {"sensor", f.sensor_ms},
                    {"image", f.image_ms},
                    {"total", f.trace_ms + f.shade_ms + f.sensor_ms + f.image_ms}};
    j["display_range_db"] = {f.display.lo_db, f.display.hi_db};
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

#include "ui/model/render_worker.hpp"

#include "core/display/display_range.hpp"

#include "core/io/ping_output.hpp"
#include "core/base/timing.hpp"

#include <algorithm>
#include <exception>

namespace sonarsim::ui {
namespace {

/// A side-scan's or scan's pings of `scene` into `r`, with the image its PNG shows; `cancel` stops them.
/// `traces` keeps the hits from one request to the next: a slider of the mission re-shades them (and, with
/// `keep_placement`, keeps them at rest while their estimate made anew serves: kept_placement_serves).
void render_pings_into(RenderResult& r, const SceneDesc& scene, bool preview, bool ground_truth,
                       bool keep_placement, std::vector<Ping> pings, const std::atomic<bool>& cancel,
                       PingTraces& traces) {
    PingControl control;
    control.keep_placement = keep_placement;
    control.schedule = std::move(pings);
    control.cancel = &cancel;
    control.preview = preview;
    control.ground_truth = ground_truth && !preview;
    auto series = std::make_shared<const PingSeries>(render_pings(scene, control, &traces));
    r.ping_image = std::make_shared<const Image8>(ping_image(scene, *series, ping_views(scene, *series)));
    r.pings = std::move(series);
    r.preview_pings = preview;
    r.scene = scene;
    r.stage = Stage::Trace;
}

} // namespace

RenderWorker::RenderWorker() : thread_([this] { loop(); }) {}

RenderWorker::~RenderWorker() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
        cancel_.store(true, std::memory_order_relaxed);
    }
    wake_.notify_all();
    thread_.join();
}

std::uint64_t RenderWorker::request(const SceneDesc& scene, bool preview, bool ground_truth,
                                    std::optional<Stage> changed, int fan_height_px, std::vector<Ping> pings,
                                    bool keep_placement) {
    std::uint64_t id;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        id = next_id_++;
        // A replaced request's change still has to be made: the earlier of the two stages.
        if (changed && queued_)
            changed = queued_->changed ? std::min(*changed, *queued_->changed) : queued_->changed;
        queued_ =
            Job{id, scene, preview, ground_truth, changed, fan_height_px, std::move(pings), keep_placement};
        // Restart on change: a full render of an outdated scene is stopped inside its trace. A running
        // preview is let finish (a few ms): cancelling previews in favour of newer previews while the user
        // drags would show nothing at all.
        if (running_id_ != 0 && !running_preview_) cancel_.store(true, std::memory_order_relaxed);
    }
    wake_.notify_one();
    return id;
}

std::optional<RenderResult> RenderWorker::take() {
    std::lock_guard<std::mutex> lock(mutex_);
    std::optional<RenderResult> r = std::move(result_);
    result_.reset();
    return r;
}

bool RenderWorker::wait_for(std::uint64_t id, std::chrono::milliseconds timeout) {
    std::unique_lock<std::mutex> lock(mutex_);
    return done_.wait_for(lock, timeout, [&] { return finished_id_ >= id; });
}

void RenderWorker::set_notify(std::function<void()> notify) {
    std::lock_guard<std::mutex> lock(notify_mutex_);
    notify_ = std::move(notify);
}

std::uint64_t RenderWorker::running_id() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return running_id_;
}

std::uint64_t RenderWorker::cancelled_count() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return cancelled_;
}

bool RenderWorker::busy() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return running_id_ != 0 || queued_.has_value();
}

void RenderWorker::loop() {
    std::unique_ptr<Simulator> sim; // its own Simulator: core's is not thread-safe
    Stage carried = Stage::None;    // what cancelled renders had started to recompute
    bool known = false;             // the simulator holds the previous request's scene
    PingTraces ping_traces;         // a side-scan's or scan's hits, from request to request
    for (;;) {
        Job job;
        {
            std::unique_lock<std::mutex> lock(mutex_);
            wake_.wait(lock, [&] { return stop_ || queued_.has_value(); });
            if (stop_) return;
            job = std::move(*queued_);
            queued_.reset();
            running_id_ = job.id;
            // A preview of pings may trace every ping: as long as a full image, so a newer request cancels
            // its tracing (its re-shading of kept pings finishes).
            running_preview_ = job.preview && job.scene.sonar.kind == SonarKind::Imaging;
            cancel_.store(false, std::memory_order_relaxed); // only requests after this one cancel it
        }
        RenderResult r;
        r.id = job.id;
        bool cancelled = false;
        const auto t0 = std::chrono::steady_clock::now();
        try {
            if (job.scene.sonar.kind != SonarKind::Imaging) { // a side-scan's or scan's pings
                render_pings_into(r, job.scene, job.preview, job.ground_truth, job.keep_placement,
                                  std::move(job.pings), cancel_, ping_traces);
                known = false; // the imaging simulator does not hold this scene
            } else {
                ping_traces = PingTraces(); // their hits go with the kind
                if (!sim) {
                    sim = std::make_unique<Simulator>(job.scene);
                    r.stage = Stage::Geometry;
                } else {
                    r.stage = known && job.changed ? *job.changed : changed_stage(sim->scene(), job.scene);
                    known = false;
                    sim->set_scene(job.scene, r.stage); // a bad mesh throws; the last good geometry stays
                }
                known = true;
                sim->set_fan_height_px(job.fan_height_px); // a new height re-forms the fan only
                TraceControl control;
                control.cancel = &cancel_;
                control.preview = job.preview;
                // A slider that steers the sampler re-shades the kept hits and re-traces only where their
                // estimate, made anew, no longer serves (kept_placement_serves).
                control.keep_placement = job.keep_placement;
                // A preview that traces (a drag; a slider of the sonar's geometry) is made to the screen's
                // precision (the adaptive scheme), with its estimate; one that re-shades traces nothing.
                if (job.preview) control.preview_median_db = half_grey_level_db(sim->display());
                // Full-quality frames carry each cell's strongest contribution (hovering draws its path
                // without shading anything) and, when asked for, the ground truth, all made in the shading
                // pass.
                sim->request({job.ground_truth && !job.preview, !job.preview});
                r.frame = sim->render(control); // shares its stages with the simulator: no copy
                r.scene = sim->scene();
                r.ground_truth = r.frame->truth_ptr;
                r.stage = std::min(r.stage, carried);
                carried = Stage::None;
            }
        } catch (const TraceCancelled&) {
            cancelled = true; // the simulator keeps its stale stages stale; a newer request is queued
            carried = std::min(carried, r.stage);
        } catch (const std::exception& e) {
            r.error = e.what();
            r.scene = job.scene;
            r.frame.reset();
        }
        r.wall_ms = ms_since(t0);
        {
            std::lock_guard<std::mutex> lock(mutex_);
            running_id_ = 0, running_preview_ = false;
            if (cancelled) {
                ++cancelled_;
                continue;
            }
            result_ = std::move(r);
            finished_id_ = job.id;
        }
        done_.notify_all();
        std::lock_guard<std::mutex> lock(notify_mutex_);
        if (notify_) notify_();
    }
}

} // namespace sonarsim::ui

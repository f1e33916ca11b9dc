// The sonar image off the UI thread: a worker thread with its own Simulator. A newer request supersedes
// older ones that have not started, and cancels a running full-quality render inside its trace (a running
// preview is let finish: it takes a few ms, and it is what a drag shows). Results come back under a mutex as
// shared immutable frames. The UI never waits unless it asks to.
#pragma once
#include "core/geometry/mesh.hpp"
#include "core/shading/ground_truth.hpp"
#include "core/kinds/ping_series.hpp"
#include "core/pipeline/simulator.hpp"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace sonarsim::ui {

struct RenderResult {
    std::uint64_t id = 0;               ///< the request it answers
    SceneDesc scene;                    ///< the scene the frame was made from (on error: the rejected one)
    std::shared_ptr<const Frame> frame; ///< null on error; frame->preview(): a coarse preview
    std::shared_ptr<const GroundTruth> ground_truth; ///< when requested, for full-quality frames only
    std::string error;         ///< InputError::what() (or another exception's) on failure
    Stage stage = Stage::None; ///< first stage recomputed (Stage::Geometry: meshes rebuilt)
    double wall_ms = 0;        ///< set_scene + render, as measured by the worker
    /// A side-scan's or scanning sonar's pings (sonar.kind), with the image its PNG shows (the waterfall or
    /// the sweep); `frame` is null then.
    std::shared_ptr<const PingSeries> pings;
    std::shared_ptr<const Image8> ping_image;
    bool preview_pings = false; ///< the pings were traced as previews (each ping's base grid only)

    /// A drag's preview, never to be taken for the full-quality image.
    bool preview() const { return frame ? frame->preview() : preview_pings; }
};

class RenderWorker {
  public:
    RenderWorker();
    ~RenderWorker();
    RenderWorker(const RenderWorker&) = delete;
    RenderWorker& operator=(const RenderWorker&) = delete;

    /// Queues a scene; replaces a queued one that has not started and cancels a running full render.
    /// `preview`: TraceControl::preview (the adaptive sampler's base grid only, or the kept hits re-shaded
    /// when only values that steer the sampler changed). Returns the request id
    /// (increasing).
    /// `changed`: changed_stage from the scene of the previous request to this one, when the caller knows it
    /// (computed once per edit); otherwise the worker compares the scenes itself.
    /// `fan_height_px`: Simulator::set_fan_height_px (0: one row per range bin).
    /// `pings`: a side-scan's or scan's pings to hear (PingControl::schedule; empty: the scene's own).
    /// `keep_placement`: TraceControl::keep_placement (a slider that steers the sampler keeps the hits
    /// while their estimate made anew serves: kept_placement_serves); false places the rays anew, as
    /// `render` does.
    std::uint64_t request(const SceneDesc& scene, bool preview = false, bool ground_truth = false,
                          std::optional<Stage> changed = std::nullopt, int fan_height_px = 0,
                          std::vector<Ping> pings = {}, bool keep_placement = true);
    /// The newest finished result not yet taken, if any (older unread results are dropped).
    std::optional<RenderResult> take();
    /// Waits until the result of request `id` (or a newer one) is done; false on timeout.
    bool wait_for(std::uint64_t id, std::chrono::milliseconds timeout);
    /// True while a request is queued or being rendered.
    bool busy() const;
    /// Called on the worker thread after each result (e.g. to wake a UI event loop). Once set_notify
    /// returns, the previous function is not running and will not be called again.
    void set_notify(std::function<void()> notify);
    /// Renders stopped inside their trace by a newer request so far.
    std::uint64_t cancelled_count() const;
    /// The request being rendered now (0: none).
    std::uint64_t running_id() const;

  private:
    void loop();

    mutable std::mutex mutex_;
    std::condition_variable wake_, done_;
    struct Job {
        std::uint64_t id = 0;
        SceneDesc scene;
        bool preview = false;
        bool ground_truth = false;
        std::optional<Stage> changed; ///< changed_stage from the previous request's scene, if known
        int fan_height_px = 0;
        std::vector<Ping> pings;
        bool keep_placement = true;
    };
    std::optional<Job> queued_;
    std::optional<RenderResult> result_;
    std::uint64_t next_id_ = 1, finished_id_ = 0, cancelled_ = 0, running_id_ = 0;
    bool running_preview_ = false, stop_ = false;
    std::atomic<bool> cancel_{false}; ///< set (under mutex_) to stop the running trace
    std::mutex notify_mutex_;
    std::function<void()> notify_;
    std::thread thread_;
};

} // namespace sonarsim::ui

#include "render_worker.hpp"

#include <exception>

namespace sonarsim::ui {
namespace {
double ms_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

} // namespace

RenderWorker::RenderWorker() : thread_([this] { loop(); }) {}

RenderWorker::~RenderWorker() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
    }
    wake_.notify_all();
    thread_.join();
}

std::uint64_t RenderWorker::request(const SceneDesc& scene) {
    std::uint64_t id;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        id = next_id_++;
        queued_.emplace(id, scene);
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

bool RenderWorker::busy() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return running_ || queued_.has_value();
}

void RenderWorker::loop() {
    std::unique_ptr<Simulator> sim; // its own Simulator: core's is not thread-safe
    for (;;) {
        std::pair<std::uint64_t, SceneDesc> job;
        {
            std::unique_lock<std::mutex> lock(mutex_);
            wake_.wait(lock, [&] { return stop_ || queued_.has_value(); });
            if (stop_) return;
            job = std::move(*queued_);
            queued_.reset();
            running_ = true;
        }
        RenderResult r;
        r.id = job.first;
        const auto t0 = std::chrono::steady_clock::now();
        try {
            if (!sim) {
                sim = std::make_unique<Simulator>(job.second);
                r.stage = Stage::Geometry;
            } else {
                r.stage = changed_stage(sim->scene(), job.second);
                sim->set_scene(job.second); // a bad mesh throws; the last good geometry stays
            }
            r.frame = std::make_shared<const Frame>(sim->render());
            r.scene = sim->scene();
        } catch (const std::exception& e) {
            r.error = e.what();
            r.scene = job.second;
            r.frame.reset();
        }
        r.wall_ms = ms_since(t0);
        {
            std::lock_guard<std::mutex> lock(mutex_);
            result_ = std::move(r);
            finished_id_ = job.first;
            running_ = false;
        }
        done_.notify_all();
        std::lock_guard<std::mutex> lock(notify_mutex_);
        if (notify_) notify_();
    }
}

} // namespace sonarsim::ui

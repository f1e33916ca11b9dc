// The render worker under load: a newer request stops a running full render inside its trace, so the newer
// image arrives in far less time than the old render takes alone; a running preview is let finish.
#include "ui/model/render_worker.hpp"
#include "core/scene/sampling_scheme.hpp"

#include "core/scene/scene_io.hpp"

#include <catch2/catch.hpp>
#include <chrono>
#include <cstdio>
#include <thread>

using namespace sonarsim;
using namespace std::chrono_literals;

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

/// The Fig. 9 scene with 2000 x 9 spread rays per beam (2.3 M rays): a render of several hundred ms.
SceneDesc slow_scene() {
    SceneDesc s = default_scene();
    set_scheme(s.sampling, SamplingScheme::Spread);
    s.sampling.elevation_rays = 2000;
    s.sampling.azimuth_rays = 9;
    return s;
}

/// The same scene with 101 spread rays per beam (170x fewer).
SceneDesc cheap_scene() {
    SceneDesc s = default_scene();
    set_scheme(s.sampling, SamplingScheme::Spread);
    return s;
}

/// Request `s` and wait for its image; the worker's own time for it.
double render_ms(ui::RenderWorker& worker, const SceneDesc& s, bool preview = false) {
    const auto id = worker.request(s, preview);
    REQUIRE(worker.wait_for(id, 300s));
    auto r = worker.take();
    REQUIRE(r);
    REQUIRE(r->id == id);
    REQUIRE(r->frame);
    return r->wall_ms;
}

/// Waits until the worker is rendering request `id`.
void wait_until_started(const ui::RenderWorker& worker, std::uint64_t id) {
    const auto t0 = Clock::now();
    while (worker.running_id() != id && ms_since(t0) < 60000) std::this_thread::sleep_for(1ms);
    REQUIRE(worker.running_id() == id);
}

} // namespace

TEST_CASE("a newer request cancels a running full render inside its trace", "[ui][worker]") {
    ui::RenderWorker worker;
    render_ms(worker, cheap_scene()); // geometry built, first-use costs paid
    SceneDesc slow = slow_scene();
    const double slow_alone_ms = render_ms(worker, slow);
    render_ms(worker, cheap_scene());

    slow.sonar.pose.orientation_deg[2] += 1; // a new pose: it must re-trace
    const auto slow_id = worker.request(slow);
    wait_until_started(worker, slow_id);
    SceneDesc cheap = cheap_scene();
    cheap.sonar.pose.orientation_deg[2] += 2;
    const auto t0 = Clock::now();
    const auto cheap_id = worker.request(cheap);
    REQUIRE(worker.wait_for(cheap_id, 300s));
    const double superseded_ms = ms_since(t0);
    auto r = worker.take();
    REQUIRE(r);
    CHECK(r->id == cheap_id);
    REQUIRE(r->frame);
    CHECK(r->scene.sonar.pose.orientation_deg[2] == cheap.sonar.pose.orientation_deg[2]);
    CHECK(r->frame->hits().rays_traced == std::uint64_t(cheap.sonar.beams) * 101);
    CHECK(worker.cancelled_count() == 1);
    CHECK(worker.wait_for(slow_id, 1ms)); // the cancelled request counts as superseded
    std::printf("worker: slow render alone %.0f ms; cheap request behind a cancelled slow one %.0f ms "
                "(cheap alone %.0f ms)\n",
                slow_alone_ms, superseded_ms, r->wall_ms);
    // Without cancellation the cheap image would wait for the rest of the slow render.
    CHECK(superseded_ms < 0.5 * slow_alone_ms);

    // The simulator stayed consistent: the slow scene renders as if nothing had been cancelled.
    const auto id = worker.request(slow);
    REQUIRE(worker.wait_for(id, 300s));
    r = worker.take();
    REQUIRE(r->frame);
    CHECK(r->stage == Stage::Trace);
    CHECK(r->frame->hits().rays_traced == std::uint64_t(slow.sonar.beams) * 2000 * 9);
}

TEST_CASE("a running preview is let finish", "[ui][worker]") {
    ui::RenderWorker worker;
    render_ms(worker, cheap_scene());
    // Spread ignores TraceControl::preview: this "preview" is a slow full render.
    const auto slow_id = worker.request(slow_scene(), true);
    wait_until_started(worker, slow_id);
    const auto cheap_id = worker.request(cheap_scene());
    REQUIRE(worker.wait_for(cheap_id, 300s));
    CHECK(worker.cancelled_count() == 0);
    CHECK(worker.wait_for(slow_id, 1ms));
    auto r = worker.take(); // the newest result; the slow one was finished and then replaced
    REQUIRE(r);
    CHECK(r->id == cheap_id);
}

TEST_CASE("the worker passes the preview flag to the adaptive trace", "[ui][worker]") {
    ui::RenderWorker worker;
    SceneDesc s = default_scene();
    auto id = worker.request(s, true);
    REQUIRE(worker.wait_for(id, 300s));
    auto r = worker.take();
    REQUIRE(r->frame);
    CHECK(r->frame->preview());
    id = worker.request(s); // the same scene in full quality: re-traced
    REQUIRE(worker.wait_for(id, 300s));
    r = worker.take();
    REQUIRE(r->frame);
    CHECK_FALSE(r->frame->preview());
    CHECK(r->frame->hits().error_estimate.valid);
}

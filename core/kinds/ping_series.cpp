#include "core/kinds/ping_series.hpp"

#include "core/base/timing.hpp"
#include "core/pipeline/simulator.hpp"
#include "core/shading/physics.hpp"

#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

namespace sonarsim {

double first_return_m(const PingSeries& s, int ping, double threshold_db) {
    for (int k = 0; k < s.bins; ++k)
        for (int ch = 0; ch < s.channels; ++ch) {
            const size_t at = (size_t(ping) * size_t(s.channels) + size_t(ch)) * size_t(s.bins) + size_t(k);
            if (s.ideal_db[at] >= threshold_db) return s.grid->bin_near_edge_m(k);
        }
    return std::numeric_limits<double>::quiet_NaN();
}

PingSeries render_pings(const SceneDesc& scene, const PingControl& control, PingTraces* traces) {
    const auto t0 = std::chrono::steady_clock::now();
    PingSeries out;
    out.kind = scene.sonar.kind;
    out.channels = channel_count(scene.sonar.kind);
    out.schedule = ping_schedule(scene);
    out.pings = int(out.schedule.size());
    out.bins = scene.sonar.range_bins;
    const SceneDesc beam = beam_scene(scene);
    out.grid = sonar_grid(beam.sonar);
    out.ping_interval_s =
        kind_ping_interval_s(scene, sound_speed_m_s(scene.water.temperature_c, scene.water.depth_m));
    const size_t n = size_t(out.pings) * size_t(out.channels) * size_t(out.bins);
    out.level_db.resize(n), out.ideal_db.resize(n);
    if (control.ground_truth) out.truth.resize(size_t(out.pings) * size_t(out.channels));
    // Each ping and channel ("job") is shaded from hits: kept from an earlier series (traces), traced by
    // the first job of this series heard from its pose (a still sonar's pings share one trace per channel),
    // or its own. Those that trace run first, then the others; both in parallel, each thread with one
    // simulator per channel, which keeps its geometry and its stages' buffers from ping to ping. A ping's
    // image does not depend on which simulator made it, so the series is the same whatever the threads.
    const size_t jobs = size_t(out.pings) * size_t(out.channels);
    if (traces) traces->prepare(beam, control.preview);
    std::vector<Pose> poses(jobs);
    std::vector<std::shared_ptr<const TraceResult>> hits(jobs);
    std::vector<size_t> traced_by(jobs); // the job whose trace a job shades (itself: it traces)
    std::map<PingKey, size_t> first;
    std::vector<size_t> tracing, shading;
    for (size_t j = 0; j < jobs; ++j) {
        const int ch = int(j % size_t(out.channels));
        poses[j] = transducer_pose(scene, out.schedule[j / size_t(out.channels)], ch);
        const PingKey key(ch, poses[j]);
        if (traces) hits[j] = traces->find(key, control.preview);
        const auto [it, is_first] = first.emplace(key, j);
        traced_by[j] = it->second;
        (hits[j] || !is_first ? shading : tracing).push_back(j);
    }
    struct Worker {
        std::vector<std::unique_ptr<Simulator>> sims;
        std::uint64_t rays = 0;
        double stage_ms[4] = {0, 0, 0, 0};
    };
    tbb::enumerable_thread_specific<Worker> workers;
    TraceControl trace;
    trace.cancel = control.cancel;
    trace.preview = control.preview;
    std::mutex progress_mutex;
    size_t done = 0;
    const auto run = [&](size_t j) {
        Worker& w = workers.local();
        if (w.sims.empty())
            for (int ch = 0; ch < out.channels; ++ch) {
                w.sims.push_back(std::make_unique<Simulator>(beam));
                w.sims.back()->request({control.ground_truth, false});
                w.sims.back()->set_forms_fan(false); // a ping's levels are all the series needs
            }
        const size_t p = j / size_t(out.channels), ch = j % size_t(out.channels);
        SceneDesc at = beam;
        at.sonar.pose = poses[j];
        at.sensor.noise_draw = std::uint64_t(p) + 1; // each ping its own noise, even from one pose
        Simulator& sim = *w.sims[ch];
        sim.set_scene(at, Stage::Trace);
        const std::shared_ptr<const TraceResult> kept =
            hits[j] ? hits[j] : hits[traced_by[j]]; // null: traces
        if (kept) sim.set_hits(kept); // shading only: not cancelled (a slider's re-shade always shows)
        const auto f = sim.render(trace);
        if (!kept) { // its hits are read by the shading jobs after every trace is done
            hits[j] = f->hits_ptr;
            w.rays += f->hits().rays_traced;
        }
        const double times[4] = {f->trace_ms, f->shade_ms, f->sensor_ms, f->image_ms};
        for (int k = 0; k < 4; ++k) w.stage_ms[k] += times[k];
        const size_t off = j * size_t(out.bins);
        std::memcpy(out.level_db.data() + off, f->polar().level_db.data(), size_t(out.bins) * 4);
        std::memcpy(out.ideal_db.data() + off, f->ideal().level_db.data(), size_t(out.bins) * 4);
        if (control.ground_truth) out.truth[j] = *f->truth_ptr;
        if (control.progress) {
            std::lock_guard<std::mutex> lock(progress_mutex);
            if (++done % size_t(out.channels) == 0) control.progress(int(done) / out.channels, out.pings);
        }
    };
    for (const std::vector<size_t>* phase : {&tracing, &shading})
        tbb::parallel_for(tbb::blocked_range<size_t>(0, phase->size(), 4), [&](const auto& r) {
            for (size_t i = r.begin(); i != r.end(); ++i) run((*phase)[i]);
        });
    if (traces) {
        std::map<PingKey, std::shared_ptr<const TraceResult>> series_hits;
        for (const auto& [key, j] : first) series_hits.emplace(key, hits[j] ? hits[j] : hits[traced_by[j]]);
        traces->keep(std::move(series_hits));
    }
    for (const Worker& w : workers) {
        out.rays_traced += w.rays;
        for (int k = 0; k < 4; ++k) out.stage_ms[k] += w.stage_ms[k];
    }
    if (out.kind == SonarKind::Sidescan) {
        out.first_return_m.resize(size_t(out.pings));
        for (int p = 0; p < out.pings; ++p)
            out.first_return_m[size_t(p)] = first_return_m(out, p, scene.sidescan.bottom_threshold_db);
    }
    out.trace_ms = ms_since(t0);
    return out;
}

} // namespace sonarsim

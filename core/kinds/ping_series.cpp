#include "core/kinds/ping_series.hpp"

#include "core/base/timing.hpp"
#include "core/pipeline/simulator.hpp"
#include "core/sampling/trace.hpp"
#include "core/shading/physics.hpp"

#include <chrono>
#include <cmath>
#include <algorithm>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

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
    out.schedule = control.schedule.empty() ? ping_schedule(scene) : control.schedule;
    out.pings = int(out.schedule.size());
    out.bins = scene.sonar.range_bins;
    const SceneDesc beam = beam_scene(scene);
    out.grid = sonar_grid(beam.sonar);
    out.ping_interval_s =
        kind_ping_interval_s(scene, sound_speed_m_s(scene.water.temperature_c, scene.water.depth_m));
    const size_t n = size_t(out.pings) * size_t(out.channels) * size_t(out.bins);
    out.level_db.resize(n), out.ideal_db.resize(n);
    if (control.ground_truth) out.truth.resize(size_t(out.pings) * size_t(out.channels));
    // Each ping and channel ("job") is copied from the levels an earlier series made (traces, when nothing
    // but poses changed), or shaded from hits: kept from an earlier series (traces), traced by the first job
    // of this series heard from its pose (a still sonar's pings share one trace per channel), or its own.
    // Those that trace run first, then those that shade; both in parallel, each thread with one simulator
    // per channel, which keeps its geometry and its stages' buffers from ping to ping. A ping's image does
    // not depend on which simulator made it, so the series is the same whatever the threads.
    const size_t jobs = size_t(out.pings) * size_t(out.channels);
    if (traces) traces->prepare(beam, control.preview, control.keep_placement);
    std::vector<PingKey> keys;
    std::vector<std::uint64_t> draws(jobs);
    std::vector<std::shared_ptr<const TraceResult>> hits(jobs);
    std::vector<std::shared_ptr<const PingLevels>> levels(jobs);
    std::vector<size_t> traced_by(jobs); // the job whose trace a job shades (itself: it traces)
    keys.reserve(jobs);
    for (size_t j = 0; j < jobs; ++j) {
        const int ch = int(j % size_t(out.channels));
        const Ping& ping = out.schedule[j / size_t(out.channels)];
        keys.emplace_back(ch, transducer_pose(scene, ping, ch));
        draws[j] = ping_noise_draw(ping.number); // even from one pose, its own noise
        traced_by[j] = j;
        if (traces) {
            hits[j] = traces->find(keys[j], control.preview);
            if (!control.ground_truth) levels[j] = traces->find_levels(keys[j], draws[j], control.preview);
        }
    }
    // Kept hits placed for an earlier shading (keep_placement): their estimate made anew with this shading,
    // once per pose, before anything runs (from a kept profile's L_EN where a preview of this scene shaded
    // them, else from the hits); a pose whose rays no longer serve (kept_placement_serves, as
    // Simulator::render keeps an image's) is traced again like one with no kept hits.
    if (traces && control.keep_placement && !control.preview) {
        std::map<PingKey, size_t> check; // a job of each pose to check, one with kept levels if any
        for (size_t j = 0; j < jobs; ++j)
            if (hits[j] && traces->needs_estimate(keys[j]))
                if (const auto [it, added] = check.emplace(keys[j], j);
                    !added && levels[j] && !levels[it->second])
                    it->second = j;
        const std::vector<std::pair<PingKey, size_t>> poses(check.begin(), check.end());
        std::vector<char> serves(poses.size(), 1);
        tbb::parallel_for(size_t(0), poses.size(), [&](size_t i) {
            const size_t j = poses[i].second;
            const TraceResult& h = *hits[j];
            if (!h.estimate_cells) return void(serves[i] = 0);
            SceneDesc at = beam;
            at.sonar.pose = keys[j].as_pose();
            PolarImage ideal;
            if (levels[j]) ideal.bins = out.bins, ideal.beams = 1, ideal.level_db = levels[j]->ideal_db;
            serves[i] = kept_placement_serves(reestimate_error(h, at, levels[j] ? &ideal : nullptr),
                                              h.error_estimate, at.sampling);
        });
        std::set<PingKey> missed;
        for (size_t i = 0; i < poses.size(); ++i)
            if (!serves[i]) missed.insert(poses[i].first);
        for (size_t j = 0; j < jobs; ++j)
            if (missed.count(keys[j])) hits[j] = nullptr, levels[j] = nullptr;
    }
    // Profiles from kept hits placed for an earlier shading (shaded or copied below).
    for (size_t j = 0; j < jobs; ++j)
        out.kept_placement_profiles += (hits[j] || levels[j]) && traces->placed_earlier(keys[j]);
    std::map<PingKey, size_t> first;
    std::vector<size_t> tracing, shading;
    for (size_t j = 0; j < jobs; ++j) {
        if (levels[j]) continue; // copied below
        if (hits[j]) {
            shading.push_back(j);
            continue;
        }
        const auto [it, is_first] = first.emplace(keys[j], j);
        traced_by[j] = it->second;
        (is_first ? tracing : shading).push_back(j);
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
    trace.keep_placement = control.keep_placement;
    std::mutex progress_mutex;
    size_t done = jobs - tracing.size() - shading.size(); // the copied ones
    out.traced_profiles = int(tracing.size()), out.shaded_profiles = int(shading.size());
    out.copied_profiles = int(done);
    const auto run = [&](size_t j) {
        Worker& w = workers.local();
        if (w.sims.empty())
            for (int ch = 0; ch < out.channels; ++ch) {
                w.sims.push_back(std::make_unique<Simulator>(beam));
                w.sims.back()->request({control.ground_truth, false});
                w.sims.back()->set_forms_fan(false); // a ping's levels are all the series needs
            }
        const size_t ch = j % size_t(out.channels);
        SceneDesc at = beam;
        at.sonar.pose = keys[j].as_pose();
        at.sensor.noise_draw = draws[j];
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
    const auto run_phase = [&](const std::vector<size_t>& phase) {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, phase.size(), 4), [&](const auto& r) {
            // Isolated: a thread waiting in a render's own parallel loops takes no other ping, which would
            // use this thread's simulator while that render is on its stack.
            for (size_t i = r.begin(); i != r.end(); ++i)
                tbb::this_task_arena::isolate([&] { run(phase[i]); });
        });
    };
    try {
        run_phase(tracing);
    } catch (const TraceCancelled&) {
        // The traces finished before the cancel are kept (every task has ended once parallel_for throws;
        // they replace kept hits placed for an earlier shading): a series cancelled again and again, as along
        // a played trajectory, still gets on.
        if (traces) {
            std::map<PingKey, std::shared_ptr<const TraceResult>> finished;
            for (size_t j : tracing)
                if (hits[j]) finished.emplace(keys[j], hits[j]);
            traces->add(std::move(finished));
        }
        throw;
    }
    run_phase(shading);
    for (size_t j = 0; j < jobs; ++j) {
        if (!levels[j]) continue;
        const size_t off = j * size_t(out.bins);
        std::copy(levels[j]->level_db.begin(), levels[j]->level_db.end(), out.level_db.begin() + long(off));
        std::copy(levels[j]->ideal_db.begin(), levels[j]->ideal_db.end(), out.ideal_db.begin() + long(off));
    }
    if (control.progress && tracing.empty() && shading.empty()) control.progress(out.pings, out.pings);
    if (traces) {
        std::map<PingKey, std::shared_ptr<const TraceResult>> series_hits;
        std::map<PingTraces::LevelsKey, std::shared_ptr<const PingLevels>> series_levels;
        for (size_t j = 0; j < jobs; ++j) {
            if (hits[j]) series_hits.emplace(keys[j], hits[j]);
            if (!levels[j]) {
                auto made = std::make_shared<PingLevels>();
                const auto at = long(j * size_t(out.bins)), end = at + out.bins;
                made->level_db.assign(out.level_db.begin() + at, out.level_db.begin() + end);
                made->ideal_db.assign(out.ideal_db.begin() + at, out.ideal_db.begin() + end);
                const auto& used = hits[j] ? hits[j] : hits[traced_by[j]]; // a preview may shade kept hits
                made->preview = control.preview && (!used || used->preview);
                levels[j] = std::move(made);
            }
            series_levels.emplace(PingTraces::LevelsKey{keys[j], draws[j]}, levels[j]);
        }
        traces->keep(beam, std::move(series_hits), std::move(series_levels),
                     !control.preview && control.keep_placement);
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

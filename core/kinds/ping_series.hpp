// A side-scan's or scanning sonar's pings traced and shaded: per ping and channel one range profile (the
// one-beam imaging sonar's image through the sensor stage), the pose and time it was heard from, and for a
// side-scan the altitude of its first bottom return.
#pragma once
#include "core/grid/sonar_grid.hpp"
#include "core/kinds/ping_traces.hpp"
#include "core/kinds/pings.hpp"
#include "core/shading/ground_truth.hpp"

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

namespace sonarsim {

/// The traced pings of one waterfall or sweep.
struct PingSeries {
    SonarKind kind = SonarKind::Imaging;
    int pings = 0, channels = 0, bins = 0;
    std::shared_ptr<const SonarGrid> grid; ///< one channel's beam and its bins
    double ping_interval_s = 0;
    std::vector<Ping> schedule; ///< when and from where each ping was heard
    std::vector<float>
        level_db; ///< through the sensor [dB], index [(ping * channels + channel) * bins + bin]
    std::vector<float> ideal_db; ///< L_EN before the sensor, same layout
    /// Side-scan: each ping's first bottom return (sidescan.bottom_threshold_db on L_EN, either channel): the
    /// near edge of its bin [m]; NaN where no bin reaches it.
    std::vector<double> first_return_m;
    /// Ground truth per sample (PingControl::ground_truth, else empty): one per ping and channel, in
    /// level_db's order, each of the shape (bins, 1): what echoed into each sample, as an imaging sonar's.
    std::vector<GroundTruth> truth;
    std::uint64_t rays_traced = 0;
    /// Of the pings' profiles (one per ping and channel): traced, shaded from hits traced before (the same
    /// pose in this series or kept, PingTraces), and copied from kept levels.
    int traced_profiles = 0, shaded_profiles = 0, copied_profiles = 0;
    /// Of all the profiles: from hits placed for an earlier shading and kept, shaded or copied
    /// (PingControl::keep_placement), so the series is not the bytes a fresh one makes.
    int kept_placement_profiles = 0;
    double trace_ms = 0; ///< the pings' wall-clock time, all stages included
    /// The stages' times summed over pings and channels, on every thread (Frame's trace, shade, sensor,
    /// image).
    double stage_ms[4] = {0, 0, 0, 0};

    const float* profile(int ping, int channel) const {
        return level_db.data() + (size_t(ping) * size_t(channels) + size_t(channel)) * size_t(bins);
    }
};

/// What render_pings reports and obeys while it runs.
struct PingControl {
    /// Called after each ping with (pings done, pings in all), one call at a time from the threads that trace
    /// the pings; may be empty.
    std::function<void(int, int)> progress;
    const std::atomic<bool>* cancel = nullptr; ///< set: the current ping's trace throws TraceCancelled
    bool ground_truth = false;                 ///< also make PingSeries::truth (in the shading pass)
    bool preview = false; ///< each ping traced as a preview (TraceControl::preview: the base grid only)
    /// TraceControl::keep_placement for every ping: after a change of values that steer the adaptive sampler
    /// only, a full-quality series keeps the pings' hits whose error estimate, made anew with the new
    /// shading, still serves (kept_placement_serves), and traces the others again (the viewer's; render,
    /// batch, Python and a series without it place every ping's rays anew).
    bool keep_placement = false;
    /// The pings to hear (ping_schedule_along, as many as ping_schedule has); empty: ping_schedule(scene).
    std::vector<Ping> schedule;
};

/// Traces every ping of `scene` (a side-scan or scanning sonar) with its sampler and sensor. Pings heard from
/// one pose share one trace per channel. `traces`, when given, holds the hits of the series before: a ping
/// they have is shaded from them and traces nothing; they then hold this series' hits.
PingSeries render_pings(const SceneDesc& scene, const PingControl& control = {},
                        PingTraces* traces = nullptr);

/// The first bin of a ping whose L_EN reaches `threshold_db` in any channel, as the range of its near edge
/// [m]; NaN where none does.
double first_return_m(const PingSeries& series, int ping, double threshold_db);

} // namespace sonarsim

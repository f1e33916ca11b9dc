#include "core/kinds/pings.hpp"

#include "core/base/errors.hpp"
#include "core/data/pose.hpp"
#include "core/sampling/acquisition.hpp"
#include "core/shading/physics.hpp"

#include <cmath>
#include <cstdio>

namespace sonarsim {

int channel_count(SonarKind kind) {
    return kind == SonarKind::Sidescan ? 2 : 1;
}

const char* channel_name(SonarKind kind, int channel) {
    if (kind != SonarKind::Sidescan) return "beam";
    return channel == 0 ? "port" : "starboard";
}

double kind_ping_interval_s(const SceneDesc& s, double c) {
    const double listen = 2 * s.sonar.range_max_m / c;
    switch (s.sonar.kind) {
    case SonarKind::Sidescan:
        return listen + 1e-3 * s.sidescan.ping_overhead_ms;
    case SonarKind::Scanning:
        return listen + 1e-3 * s.scanning.step_overhead_ms;
    case SonarKind::Imaging:
        break;
    }
    return ping_interval_s(s.sonar, c);
}

std::string ping_timing_text(const SceneDesc& s) {
    const double c = sound_speed_m_s(s.water.temperature_c, s.water.depth_m);
    const double dt = kind_ping_interval_s(s, c), listen = 2 * s.sonar.range_max_m / c;
    const bool side = s.sonar.kind == SonarKind::Sidescan;
    const size_t pings = ping_schedule(s).size();
    char b[320];
    std::snprintf(b, sizeof b,
                  "%s: a %s every %.2f ms (2 r_max / c = %.2f ms + %.2f ms %s); %zu %s an image span %.3f s",
                  side ? "side-scan" : "scanning sonar", side ? "ping" : "step", dt * 1e3, listen * 1e3,
                  (dt - listen) * 1e3, side ? "sidescan.ping_overhead_ms" : "scanning.step_overhead_ms",
                  pings, side ? (pings == 1 ? "ping" : "pings") : (pings == 1 ? "step" : "steps"),
                  double(pings) * dt);
    return b;
}

std::vector<double> sweep_head_angles_deg(const ScanningParams& sc) {
    const double span = sc.sector_end_deg - sc.sector_start_deg;
    const double dir = span < 0 ? -1 : 1;
    const bool full = std::abs(std::abs(span) - 360) < 1e-9;
    // Steps that fit in the span; a hair of tolerance so that 360 / 0.9 is 400 steps, not 399.
    const double fit = std::abs(span) / sc.step_deg;
    const int steps = full ? int(std::lround(fit)) : int(std::floor(fit + 1e-9)) + 1;
    std::vector<double> angles(size_t(std::max(steps, 1)));
    for (size_t i = 0; i < angles.size(); ++i)
        angles[i] = sc.sector_start_deg + dir * double(i) * sc.step_deg;
    return angles;
}

std::vector<Ping> ping_schedule(const SceneDesc& s) {
    const double c = sound_speed_m_s(s.water.temperature_c, s.water.depth_m);
    const double dt = kind_ping_interval_s(s, c);
    std::vector<double> heads;
    if (s.sonar.kind == SonarKind::Scanning)
        heads = sweep_head_angles_deg(s.scanning);
    else
        heads.assign(size_t(s.sonar.kind == SonarKind::Sidescan ? s.sidescan.pings : 1), 0.0);
    std::vector<Ping> pings(heads.size());
    for (size_t i = 0; i < pings.size(); ++i) {
        pings[i].time_s = double(i) * dt;
        pings[i].vehicle = pose_at(s.sonar, pings[i].time_s);
        pings[i].head_deg = heads[i];
        pings[i].number = std::int64_t(i);
    }
    return pings;
}

std::vector<Ping> ping_schedule_along(const SceneDesc& s, const Trajectory& track, double now_s) {
    const double c = sound_speed_m_s(s.water.temperature_c, s.water.depth_m);
    const double dt = kind_ping_interval_s(s, c), t0 = track.empty() ? 0 : track.front().t_s;
    std::vector<Ping> pings = ping_schedule(s); // its count and head angles
    const auto n = std::int64_t(pings.size());
    const auto newest = std::int64_t(std::floor((now_s - t0) / dt + 1e-9));
    std::vector<double> heads(pings.size());
    for (size_t i = 0; i < pings.size(); ++i) heads[i] = pings[i].head_deg;
    for (std::int64_t i = 0; i < n; ++i) {
        Ping& p = pings[size_t(i)];
        p.number = newest - n + 1 + i;
        p.time_s = double(p.number) * dt;
        p.vehicle = trajectory_pose_at(track, t0 + p.time_s);
        p.head_deg = heads[size_t(((p.number % n) + n) % n)];
    }
    return pings;
}

std::vector<Ping> ping_schedule_along_file(const SceneDesc& s, const std::string& path,
                                           std::optional<double> at_s, const std::string& origin,
                                           const std::string& at_origin) {
    if (s.sonar.kind == SonarKind::Imaging)
        throw InputError(
            origin, "",
            "a side-scan's or scan's pings along a trajectory (sonar.kind sidescan or scanning); an "
            "imaging sonar's frames along one: sonarsim batch --trajectory");
    if (at_s && !std::isfinite(*at_s))
        throw InputError(at_origin, "", "the time on the trajectory must be a finite number of seconds");
    const Trajectory track = load_trajectory_csv(path);
    if (track.empty()) throw InputError(path, "", "the trajectory has no poses");
    const double at = at_s ? *at_s : track.back().t_s;
    if (std::abs(at - track.front().t_s) > kMaxPingTrackSpan_s) {
        char b[160];
        std::snprintf(b, sizeof b, "%g s is more than %g s from the trajectory's start (%g s)", at,
                      kMaxPingTrackSpan_s, track.front().t_s);
        throw InputError(at_origin, "", b);
    }
    return ping_schedule_along(s, track, at);
}

std::uint64_t ping_noise_draw(std::int64_t number) {
    // 1, 2, 3 ... for pings 0, 1, 2 ... (as before trajectories); pings before a trajectory's start from the
    // top of the range down.
    return number >= 0 ? std::uint64_t(number) + 1 : std::uint64_t(number); // -1 -> 2^64 - 1
}

Pose transducer_pose(const SceneDesc& s, const Ping& ping, int channel) {
    glm::dmat3 mount(1.0);
    if (s.sonar.kind == SonarKind::Sidescan)
        mount = rotation_matrix({0, s.sidescan.depression_deg, channel == 0 ? 90.0 : -90.0});
    else if (s.sonar.kind == SonarKind::Scanning)
        mount = rotation_matrix({0, 0, ping.head_deg});
    Pose p = ping.vehicle;
    p.orientation_deg = orientation_of(rotation_matrix(ping.vehicle.orientation_deg) * mount);
    return p;
}

SceneDesc beam_scene(const SceneDesc& scene) {
    SceneDesc b = scene;
    b.sonar.kind = SonarKind::Imaging;
    b.sonar.beams = 1;
    b.sonar.beam_table = "uniform";
    b.sonar.pings_per_frame = 1;
    b.sonar.velocity_mps = {0, 0, 0}; // each ping a snapshot from its transmit pose
    b.sonar.angular_rate_dps = {0, 0, 0};
    b.sidescan = {};
    b.scanning = {};
    b.display.auto_range = false; // the waterfall or sweep chooses its own range
    return b;
}

} // namespace sonarsim

// When a side-scan or scanning sonar pings and from where: the schedule of its pings (each from the
// vehicle's pose at its transmit time), each transducer's pose, and the one-beam imaging sonar that traces
// a ping. A ping is an image of one beam (per channel) with everything the imaging sonar has: the sonar
// equation, materials, the sampler, the sensor stage.
#pragma once
#include "core/data/scene.hpp"
#include "core/data/trajectory.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace sonarsim {

/// One ping of a side-scan (both channels) or of a scanning head (one channel).
struct Ping {
    double time_s = 0;   ///< transmit time after the first ping's [s]; along a trajectory, after its start
                         ///< (negative before it)
    Pose vehicle;        ///< the sonar's pose at the transmit (sonar.position and orientation moved by the
                         ///< motion rows)
    double head_deg = 0; ///< scanning: the head angle from the sonar's x axis toward port [deg]
    /// The ping's count from the first (negative: before a played trajectory's start); its noise draw.
    std::int64_t number = 0;
};

/// The sensor's noise draw of ping `number` (SensorParams::noise_draw): never 0 (an image's), one per ping.
std::uint64_t ping_noise_draw(std::int64_t number);

/// Channels of a kind: 2 for a side-scan (0 port, 1 starboard), else 1.
int channel_count(SonarKind kind);
/// "port", "starboard", or "beam".
const char* channel_name(SonarKind kind, int channel);

/// Time from one ping to the next [s]: the listening window 2 r_max / c plus the kind's overhead
/// (sidescan.ping_overhead_ms, scanning.step_overhead_ms). `sound_speed_m_s`: c.
double kind_ping_interval_s(const SceneDesc& scene, double sound_speed_m_s);

/// The timing in words, e.g. "side-scan: a ping every 81.3 ms (2 r_max / c = 80.0 ms + 1.3 ms
/// sidescan.ping_overhead_ms); 64 pings an image span 5.21 s" (c from the scene's water).
std::string ping_timing_text(const SceneDesc& scene);

/// Head angles of one sweep [deg]: from sector_start_deg toward sector_end_deg in steps of step_deg, both
/// ends included; a full circle (|end - start| = 360) without its end (it is the start).
std::vector<double> sweep_head_angles_deg(const ScanningParams& scanning);

/// The pings of one image: a side-scan's waterfall (sidescan.pings) or a scanning head's sweep.
std::vector<Ping> ping_schedule(const SceneDesc& scene);

/// The pings of one image heard along a trajectory being played (the viewer): ping k at t0 + k dt (t0 the
/// trajectory's first time, dt kind_ping_interval_s), from the trajectory's pose then (its first or last pose
/// before its start or after its end), the newest the last at or before `now_s`; as many as ping_schedule
/// has. A scan's step k turns the head to the sweep's step k mod its steps (each sweep from
/// sector_start_deg). A later time keeps the earlier pings that are still in the image: the waterfall
/// scrolls, the sweep fills.
std::vector<Ping> ping_schedule_along(const SceneDesc& scene, const Trajectory& track, double now_s);

/// How far from a trajectory's start the newest ping heard along it may be [s] (about 32 years: ping counts
/// stay exact).
constexpr double kMaxPingTrackSpan_s = 1e9;

/// ping_schedule_along the trajectory in CSV file `path` (load_trajectory_csv), the newest ping at its time
/// `at_s`, or at its end when none is given. InputError(origin, ...) for a sonar that is not a side-scan or
/// scan; InputError(at_origin, ...) for a time that is not finite or farther than kMaxPingTrackSpan_s from
/// the trajectory's start.
std::vector<Ping> ping_schedule_along_file(const SceneDesc& scene, const std::string& path,
                                           std::optional<double> at_s, const std::string& origin,
                                           const std::string& at_origin);

/// The pose of channel `channel`'s transducer at ping `ping`: a side-scan's port (+90 deg yaw) or starboard
/// (-90 deg) transducer pitched down by sidescan.depression_deg; a scanning head turned by head_deg.
Pose transducer_pose(const SceneDesc& scene, const Ping& ping, int channel);

/// The one-beam imaging sonar that traces one channel's ping: `scene` with sonar.kind imaging, one beam
/// sonar.azimuth_fov_deg wide, no motion within the ping; its pose is set per ping (transducer_pose).
SceneDesc beam_scene(const SceneDesc& scene);

} // namespace sonarsim

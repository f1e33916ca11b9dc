// Motion during a frame (the "acoustic rolling shutter"): when each echo of a frame is sent and heard, and
// where the sonar is at those times. A single-ping sonar hears range R at t = 2R/c after its transmit; an
// ARIS builds a frame from P pings, ping k firing every P-th beam at t_k = k (2 r_max / c + 0.42 ms). The
// frame's pose (sonar.position, sonar.orientation_deg) is the pose at its first transmit; the sonar moves
// on at sonar.velocity_mps (in its own frame at that instant) and turns at sonar.angular_rate_dps (body
// rates). The range window is cut into slabs short enough that the pose changes within one by at most a
// quarter of a range bin and a quarter of a beam; each (ping, slab) is traced from its receive pose.
#pragma once
#include "core/data/scene.hpp"

#include <vector>

namespace sonarsim {

/// Beams of one ping whose echoes arrive within one slab of range bins, traced from one pose.
struct AcquisitionSlot {
    int ping = 0;                   ///< the ping (0 ... P-1) that fires this slot's beams
    int bin_begin = 0, bin_end = 0; ///< the slab: range bins [begin, end)
    double t_tx_s = 0;              ///< the ping's transmit time after the frame's first transmit [s]
    double t_rx_s = 0;              ///< receive time at the slab's middle range [s]
};

/// Most slabs per ping: a faster motion keeps this many and reports its larger pose change per slab.
constexpr int kMaxMotionSlabs = 64;

/// True when the sonar moves or turns during a frame (non-zero velocity or rates).
bool moving(const SonarParams& sonar);

/// Time between the transmits of consecutive pings of one frame [s]: 2 r_max / c + 420 us (SENSORS.md
/// 1.2, ARIS FrameRate.cpp without its small per-model factor).
double ping_interval_s(const SonarParams& sonar, double sound_speed_m_s);

/// The ping (0 ... P-1) that fires beam i (beam 0 port-most): device beam N-1-i = channel x P + ping.
int ping_of_beam(const SonarParams& sonar, int beam);

/// The sonar's pose t seconds after the frame's first transmit.
Pose pose_at(const SonarParams& sonar, double t_s);

/// Every (ping, slab) of a frame in acquisition order; one slot covering everything when not moving.
std::vector<AcquisitionSlot> acquisition_slots(const SonarParams& sonar, double sound_speed_m_s);

/// Largest change of the pose within one slot: rotation [deg] and translation [m] over half a slab.
struct SlabPoseChange {
    double rotation_deg = 0, translation_m = 0;
};
SlabPoseChange slab_pose_change(const SonarParams& sonar, double sound_speed_m_s);

} // namespace sonarsim

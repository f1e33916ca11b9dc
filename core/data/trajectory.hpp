// Trajectories: one sonar pose per frame, read from a CSV file or generated (a circle around a point, a
// line).
#pragma once
#include "core/data/scene.hpp"

#include <string>
#include <vector>

namespace sonarsim {

struct TrajectoryPoint {
    double t_s = 0; ///< time of the frame [s]
    Pose pose;
};
using Trajectory = std::vector<TrajectoryPoint>;

/// The CSV header a trajectory file starts with.
constexpr const char* kTrajectoryHeader = "t,x,y,z,roll_deg,pitch_deg,yaw_deg";

/// Most frames of one trajectory (frame files are numbered with 6 digits).
constexpr size_t kMaxTrajectoryFrames = 1000000;

/// Parses CSV text: the header kTrajectoryHeader, then one row of 7 finite numbers per frame (t in s, x, y, z
/// in m, angles in deg; t must not decrease). Blank lines and lines starting with '#' are skipped. Errors are
/// InputError("FILE:LINE", column, message).
Trajectory parse_trajectory_csv(const std::string& text, const std::string& file);

/// Reads and parses a trajectory file.
Trajectory load_trajectory_csv(const std::string& path);

/// "cx,cy,cz,radius_m,height_m,frames": `frames` poses evenly around the circle of `radius_m` about the
/// vertical through (cx, cy), at cz + height_m, each looking at the centre (yaw towards it, pitched down by
/// atan(height / radius), no roll); frame k at angle 360 k / frames deg from +x, t = k / rate_hz.
Trajectory circle_trajectory(const std::string& spec, double rate_hz, const std::string& origin);

/// "x0,y0,z0,x1,y1,z1,frames": `frames` positions evenly from (x0, y0, z0) to (x1, y1, z1), both ends
/// included, all with `orientation_deg` (roll, pitch, yaw); t = k / rate_hz.
Trajectory line_trajectory(const std::string& spec, const Vec3d& orientation_deg, double rate_hz,
                           const std::string& origin);

/// Exactly one of a CSV file, a --circle spec or a --line spec (the others empty), as `batch` and the
/// Python module take them; `orientation_deg` is the line's. Throws InputError unless exactly one is given.
Trajectory make_trajectory(const std::string& csv_path, const std::string& circle, const std::string& line,
                           double rate_hz, const Vec3d& orientation_deg);

/// Sets `sonar.velocity_mps` (in the sonar's frame at frame k) and `sonar.angular_rate_dps` (body rates)
/// from the poses of frames k and k + 1 over their time difference (the last frame: k - 1 and k); zero for a
/// single frame or frames at the same time.
void set_motion_from_trajectory(SonarParams& sonar, const Trajectory& trajectory, size_t k);

/// The pose at time t, linear between samples (angles along the shorter way round), clamped to the ends; the
/// default pose for an empty trajectory.
Pose trajectory_pose_at(const Trajectory& trajectory, double t_s);

/// The trajectory as CSV text (kTrajectoryHeader, then one row per frame); parses back to the same poses.
std::string trajectory_to_csv(const Trajectory& trajectory);

} // namespace sonarsim

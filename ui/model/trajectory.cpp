#include "ui/model/trajectory.hpp"

#include "core/base/errors.hpp"
#include "core/base/file_io.hpp"
#include "core/io/output.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace sonarsim::ui {

void Trajectory::add(double t_s, const Pose& pose, bool skip_repeat) {
    if (skip_repeat && !samples_.empty() && samples_.back().pose.position_m == pose.position_m &&
        samples_.back().pose.orientation_deg == pose.orientation_deg)
        return;
    samples_.push_back({t_s, pose});
}

Pose Trajectory::at(double t) const {
    if (samples_.empty()) return Pose{};
    if (t <= samples_.front().t_s) return samples_.front().pose;
    if (t >= samples_.back().t_s) return samples_.back().pose;
    const auto it = std::upper_bound(samples_.begin(), samples_.end(), t,
                                     [](double v, const TrajectoryPoint& s) { return v < s.t_s; });
    const TrajectoryPoint &b = *it, &a = *(it - 1);
    const double span = b.t_s - a.t_s, u = span > 0 ? (t - a.t_s) / span : 1.0;
    if (u >= 1) return b.pose;
    Pose p;
    for (size_t i = 0; i < 3; ++i) {
        p.position_m[i] = a.pose.position_m[i] + u * (b.pose.position_m[i] - a.pose.position_m[i]);
        const double d = std::remainder(b.pose.orientation_deg[i] - a.pose.orientation_deg[i], 360.0);
        p.orientation_deg[i] = std::remainder(a.pose.orientation_deg[i] + u * d, 360.0);
    }
    return p;
}

std::string trajectory_csv(const Trajectory& tr) {
    return trajectory_to_csv(tr.samples()); // core's CSV: the one format batch, Python and the viewer share
}

Trajectory parse_trajectory_csv(const std::string& text, const std::string& file) {
    return Trajectory(sonarsim::parse_trajectory_csv(text, file));
}

Trajectory load_trajectory(const std::string& path) {
    return parse_trajectory_csv(
        read_file_bytes(path, kAnyFileSize, {path, "", "", "cannot read the trajectory"}), path);
}

void save_trajectory(const Trajectory& tr, const std::string& path) {
    write_files_atomically({{path, to_bytes(trajectory_csv(tr))}});
}

} // namespace sonarsim::ui

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
    shared_.reset();
}

Pose Trajectory::at(double t) const {
    return trajectory_pose_at(samples_, t);
}

bool Trajectory::passes(const Pose& pose, double t_s) const {
    if (samples_.empty()) return false;
    const Pose on = at(t_s);
    return on.position_m == pose.position_m && on.orientation_deg == pose.orientation_deg;
}

std::shared_ptr<const sonarsim::Trajectory> Trajectory::shared() const {
    if (!shared_) shared_ = std::make_shared<const sonarsim::Trajectory>(samples_);
    return shared_;
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

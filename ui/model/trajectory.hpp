// Sonar trajectories: recorded while the sonar is dragged, replayed, saved and loaded as the CSV that
// `sonarsim batch --trajectory` reads: header `t,x,y,z,roll_deg,pitch_deg,yaw_deg`, one pose per row, t in
// seconds (non-decreasing), positions in metres, angles in degrees. GL-free.
#pragma once
#include "core/data/scene.hpp"
#include "core/data/trajectory.hpp"

#include <memory>
#include <string>
#include <utility>

namespace sonarsim::ui {

/// A recorded or loaded trajectory: core's poses (sonarsim::Trajectory, what batch and Python read), with
/// recording (add) and replay (at) for the viewer.
class Trajectory {
  public:
    Trajectory() = default;
    explicit Trajectory(sonarsim::Trajectory samples) : samples_(std::move(samples)) {}
    /// Appends a pose at time t (seconds from the first sample); while recording (`skip_repeat`), a pose
    /// equal to the last one is skipped.
    void add(double t_s, const Pose& pose, bool skip_repeat = true);
    void clear() { samples_.clear(), shared_.reset(); }
    bool empty() const { return samples_.empty(); }
    size_t size() const { return samples_.size(); }
    const sonarsim::Trajectory& samples() const { return samples_; }
    double duration_s() const { return samples_.empty() ? 0 : samples_.back().t_s - samples_.front().t_s; }
    /// The pose at time t, linear between samples (angles along the shorter way round), clamped to the ends.
    Pose at(double t_s) const;
    /// Whether `pose` is the trajectory's at time t (the sonar on it: played, paused or at its end).
    bool passes(const Pose& pose, double t_s) const;
    /// The samples, shared: the same object until the trajectory changes (a pings' schedule along it).
    std::shared_ptr<const sonarsim::Trajectory> shared() const;

  private:
    sonarsim::Trajectory samples_;
    mutable std::shared_ptr<const sonarsim::Trajectory> shared_; ///< made by shared(), reset by a change
};

/// CSV text with the header and full precision (parsing it gives the same doubles).
std::string trajectory_csv(const Trajectory& trajectory);
/// Parses CSV text with core's parser (parse_trajectory_csv in core/data/trajectory.hpp): throws
/// InputError on a bad header, row, number or time order.
Trajectory parse_trajectory_csv(const std::string& text, const std::string& file);
Trajectory load_trajectory(const std::string& path);
/// Writes the CSV atomically; throws std::runtime_error.
void save_trajectory(const Trajectory& trajectory, const std::string& path);

} // namespace sonarsim::ui

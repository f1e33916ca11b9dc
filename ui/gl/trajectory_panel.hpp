// The Trajectory section of the controls panel: record the sonar's path while it is dragged, replay it,
// scrub it with a time slider, save and load it as the CSV of trajectory.hpp.
#pragma once
#include "ui/model/session.hpp"
#include "ui/model/trajectory.hpp"

#include <optional>
#include <string>

namespace sonarsim::ui {

struct TrajectoryUi {
    Trajectory track;
    bool recording = false, playing = false;
    double t_s = 0;        ///< playback / scrub position [s from the first sample]
    double record_t_s = 0; ///< time since recording started [s]
    std::string path = "trajectory.csv";

    void toggle_record(const Pose& now);
    void toggle_play();
    /// Once per frame, `dt_s` after the last: records `now` while recording; while playing, advances and
    /// returns the pose to show.
    std::optional<Pose> update(const Pose& now, double dt_s);
    /// Draws the section; returns a pose to show when the slider was moved.
    std::optional<Pose> draw(Session& session);
};

} // namespace sonarsim::ui

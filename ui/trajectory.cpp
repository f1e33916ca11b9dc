#include "trajectory.hpp"

#include "core/errors.hpp"
#include "core/output.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

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
                                     [](double v, const TrajectorySample& s) { return v < s.t_s; });
    const TrajectorySample &b = *it, &a = *(it - 1);
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
    std::string out = std::string(kTrajectoryHeader) + "\n";
    char buf[512];
    for (const TrajectorySample& s : tr.samples()) {
        const Vec3d &x = s.pose.position_m, &r = s.pose.orientation_deg;
        std::snprintf(buf, sizeof buf, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", s.t_s, x[0], x[1], x[2],
                      r[0], r[1], r[2]);
        out += buf;
    }
    return out;
}

Trajectory parse_trajectory_csv(const std::string& text, const std::string& file) {
    std::istringstream in(text);
    std::string row;
    int line = 0;
    Trajectory tr;
    double last_t = -INFINITY;
    while (std::getline(in, row)) {
        ++line;
        if (!row.empty() && row.back() == '\r') row.pop_back();
        const std::string where = "line " + std::to_string(line);
        if (line == 1) {
            if (row != kTrajectoryHeader)
                throw InputError(file, where, std::string("expected the header ") + kTrajectoryHeader);
            continue;
        }
        if (row.find_first_not_of(" \t") == std::string::npos) continue;
        std::stringstream ss(row);
        std::string cell;
        double v[7];
        int n = 0;
        while (std::getline(ss, cell, ',')) {
            if (n == 7) throw InputError(file, where, "more than 7 columns");
            try {
                size_t used = 0;
                v[n] = std::stod(cell, &used);
                if (cell.find_first_not_of(" \t", used) != std::string::npos) throw std::invalid_argument("");
            } catch (const std::exception&) {
                throw InputError(file, where, "\"" + cell + "\" is not a number");
            }
            if (!std::isfinite(v[n])) throw InputError(file, where, "values must be finite");
            ++n;
        }
        if (n != 7) throw InputError(file, where, "expected 7 columns: " + std::string(kTrajectoryHeader));
        if (v[0] < last_t) throw InputError(file, where, "t must not decrease");
        last_t = v[0];
        Pose p;
        p.position_m = {v[1], v[2], v[3]};
        p.orientation_deg = {v[4], v[5], v[6]};
        tr.add(v[0], p, false);
    }
    if (line == 0) throw InputError(file, "line 1", std::string("expected the header ") + kTrajectoryHeader);
    return tr;
}

Trajectory load_trajectory(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    if (!f) throw InputError(path, "", "cannot read the trajectory");
    std::stringstream ss;
    ss << f.rdbuf();
    return parse_trajectory_csv(ss.str(), path);
}

void save_trajectory(const Trajectory& tr, const std::string& path) {
    write_files_atomically({{path, to_bytes(trajectory_csv(tr))}});
}

} // namespace sonarsim::ui

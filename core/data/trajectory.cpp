#include "core/data/trajectory.hpp"

#include "core/base/errors.hpp"
#include "core/base/file_io.hpp"
#include "core/data/pose.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace sonarsim {
namespace {

std::string trim(const std::string& s) {
    const size_t a = s.find_first_not_of(" \t\r");
    if (a == std::string::npos) return "";
    return s.substr(a, s.find_last_not_of(" \t\r") + 1 - a);
}

std::vector<std::string> split(const std::string& s, char sep) {
    std::vector<std::string> out;
    std::stringstream ss(s);
    std::string item;
    while (std::getline(ss, item, sep)) out.push_back(trim(item));
    if (!s.empty() && s.back() == sep) out.push_back("");
    return out;
}

/// A finite number, or nothing (the whole text must be the number).
bool to_number(const std::string& text, double& x) {
    if (text.empty()) return false;
    char* end = nullptr;
    x = std::strtod(text.c_str(), &end);
    return end == text.c_str() + text.size() && std::isfinite(x);
}

/// "a,b,c,...,frames": `n_values` numbers then a frame count in [1, kMaxTrajectoryFrames].
std::vector<double> parse_spec(const std::string& spec, size_t n_values, const std::string& form,
                               const std::string& origin, size_t& frames) {
    const auto items = split(spec, ',');
    if (items.size() != n_values + 1) throw InputError(origin, "", "\"" + spec + "\": expected " + form);
    std::vector<double> v(n_values);
    for (size_t i = 0; i < n_values; ++i)
        if (!to_number(items[i], v[i]))
            throw InputError(origin, "", "\"" + items[i] + "\" is not a finite number; expected " + form);
    double n = 0;
    if (!to_number(items.back(), n) || n != std::floor(n) || n < 1 || n > double(kMaxTrajectoryFrames))
        throw InputError(origin, "",
                         "frames: \"" + items.back() + "\" is not an integer in [1, " +
                             std::to_string(kMaxTrajectoryFrames) + "]");
    frames = size_t(n);
    return v;
}

void check_rate(double rate_hz, const std::string& origin) {
    if (!(rate_hz > 0) || !std::isfinite(rate_hz))
        throw InputError(origin, "", "the frame rate must be a positive number of Hz");
}

} // namespace

Trajectory parse_trajectory_csv(const std::string& text, const std::string& file) {
    static const std::vector<std::string> columns = split(kTrajectoryHeader, ',');
    Trajectory out;
    std::istringstream in(text);
    std::string line;
    bool header = false;
    for (size_t n = 1; std::getline(in, line); ++n) {
        const std::string where = file + ":" + std::to_string(n);
        line = trim(line);
        if (line.empty() || line[0] == '#') continue;
        const auto items = split(line, ',');
        if (!header) {
            if (items != columns)
                throw InputError(where, "", "expected the header \"" + std::string(kTrajectoryHeader) + "\"");
            header = true;
            continue;
        }
        if (items.size() != columns.size())
            throw InputError(where, "",
                             "expected " + std::to_string(columns.size()) + " columns, got " +
                                 std::to_string(items.size()));
        double v[7];
        for (size_t c = 0; c < columns.size(); ++c)
            if (!to_number(items[c], v[c]))
                throw InputError(where, columns[c], "\"" + items[c] + "\" is not a finite number");
        if (!out.empty() && v[0] < out.back().t_s) {
            char prev[32];
            std::snprintf(prev, sizeof prev, "%g", out.back().t_s);
            throw InputError(where, "t", "time goes backwards (" + items[0] + " s after " + prev + " s)");
        }
        if (out.size() == kMaxTrajectoryFrames)
            throw InputError(where, "", "more than " + std::to_string(kMaxTrajectoryFrames) + " frames");
        out.push_back({v[0], {{v[1], v[2], v[3]}, {v[4], v[5], v[6]}}});
    }
    if (!header)
        throw InputError(file, "", "empty; expected the header \"" + std::string(kTrajectoryHeader) + "\"");
    if (out.empty()) throw InputError(file, "", "no frames after the header");
    return out;
}

Trajectory load_trajectory_csv(const std::string& path) {
    return parse_trajectory_csv(
        read_file_bytes(path, kAnyFileSize, {path, "", "", "trajectory file cannot be read"}), path);
}

Trajectory circle_trajectory(const std::string& spec, double rate_hz, const std::string& origin) {
    size_t frames = 0;
    const auto v = parse_spec(spec, 5, "cx,cy,cz,radius_m,height_m,frames", origin, frames);
    check_rate(rate_hz, origin);
    const double radius = v[3], height = v[4];
    if (!(radius > 0)) throw InputError(origin, "", "radius_m must be positive");
    const double pitch_deg = rad2deg(std::atan2(height, radius));
    Trajectory out(frames);
    for (size_t k = 0; k < frames; ++k) {
        const double a = 2 * kPi * double(k) / double(frames);
        Pose& p = out[k].pose;
        p.position_m = {v[0] + radius * std::cos(a), v[1] + radius * std::sin(a), v[2] + height};
        // Looking back at the centre: the yaw of the direction -(cos a, sin a), wrapped into (-180, 180].
        double yaw = rad2deg(a) + 180;
        if (yaw > 180) yaw -= 360;
        p.orientation_deg = {0, pitch_deg, yaw};
        out[k].t_s = double(k) / rate_hz;
    }
    return out;
}

Trajectory line_trajectory(const std::string& spec, const Vec3d& orientation_deg, double rate_hz,
                           const std::string& origin) {
    size_t frames = 0;
    const auto v = parse_spec(spec, 6, "x0,y0,z0,x1,y1,z1,frames", origin, frames);
    check_rate(rate_hz, origin);
    Trajectory out(frames);
    for (size_t k = 0; k < frames; ++k) {
        const double f = frames > 1 ? double(k) / double(frames - 1) : 0.0;
        for (size_t i = 0; i < 3; ++i) out[k].pose.position_m[i] = v[i] + f * (v[i + 3] - v[i]);
        out[k].pose.orientation_deg = orientation_deg;
        out[k].t_s = double(k) / rate_hz;
    }
    return out;
}

Trajectory make_trajectory(const std::string& csv_path, const std::string& circle, const std::string& line,
                           double rate_hz, const Vec3d& orientation_deg) {
    if (int(!csv_path.empty()) + int(!circle.empty()) + int(!line.empty()) != 1)
        throw InputError(
            "--trajectory", "",
            "give exactly one of --trajectory FILE, --circle cx,cy,cz,radius_m,height_m,frames or "
            "--line x0,y0,z0,x1,y1,z1,frames");
    if (!csv_path.empty()) return load_trajectory_csv(csv_path);
    if (!circle.empty()) return circle_trajectory(circle, rate_hz, "--circle");
    return line_trajectory(line, orientation_deg, rate_hz, "--line");
}

std::string trajectory_to_csv(const Trajectory& trajectory) {
    std::string text = std::string(kTrajectoryHeader) + "\n";
    char row[256];
    for (auto& p : trajectory) {
        const Vec3d &x = p.pose.position_m, &o = p.pose.orientation_deg;
        std::snprintf(row, sizeof row, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", p.t_s, x[0], x[1], x[2],
                      o[0], o[1], o[2]);
        text += row;
    }
    return text;
}

void set_motion_from_trajectory(SonarParams& sonar, const Trajectory& tr, size_t k) {
    sonar.velocity_mps = {0, 0, 0}, sonar.angular_rate_dps = {0, 0, 0};
    if (tr.size() < 2) return;
    const size_t a = k + 1 < tr.size() ? k : k - 1, b = a + 1;
    const double dt = tr[b].t_s - tr[a].t_s;
    if (!(dt > 0)) return;
    // Velocity and rates in the sonar's frame: R_a^T (p_b - p_a) / dt, and the rotation vector of
    // R_a^T R_b (its axis times its angle) / dt.
    const glm::dmat3 Ra = rotation_matrix(tr[a].pose.orientation_deg);
    const glm::dmat3 Rab = glm::transpose(Ra) * rotation_matrix(tr[b].pose.orientation_deg);
    const glm::dvec3 v =
        glm::transpose(Ra) * (to_glm(tr[b].pose.position_m) - to_glm(tr[a].pose.position_m)) / dt;
    const double cos_angle = std::clamp((Rab[0][0] + Rab[1][1] + Rab[2][2] - 1) / 2, -1.0, 1.0);
    const double angle = std::acos(cos_angle);
    glm::dvec3 axis(Rab[1][2] - Rab[2][1], Rab[2][0] - Rab[0][2], Rab[0][1] - Rab[1][0]); // 2 sin(angle) k
    const double len = glm::length(axis);
    const glm::dvec3 w = len > 0 ? axis / len * angle / dt : glm::dvec3(0.0);
    sonar.velocity_mps = {v.x, v.y, v.z};
    sonar.angular_rate_dps = {rad2deg(w.x), rad2deg(w.y), rad2deg(w.z)};
}

Pose trajectory_pose_at(const Trajectory& tr, double t) {
    if (tr.empty()) return Pose{};
    if (t <= tr.front().t_s) return tr.front().pose;
    if (t >= tr.back().t_s) return tr.back().pose;
    const auto it = std::upper_bound(tr.begin(), tr.end(), t,
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

} // namespace sonarsim

#include "core/sampling/acquisition.hpp"

#include "core/data/pose.hpp"
#include "core/grid/sonar_grid.hpp"

#include <algorithm>
#include <cmath>

namespace sonarsim {

namespace {

double norm(const Vec3d& v) {
    return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

/// Duration of the receive window of one ping [s].
double window_s(const SonarParams& s, double c) {
    return 2 * range_window_m(s) / c;
}

/// Slabs per ping: the pose may change by at most a quarter of a bin and a quarter of the narrowest beam
/// between a slab's middle and its ends.
int slabs(const SonarParams& s, double c) {
    if (!moving(s)) return 1;
    const double T = window_s(s, c);
    const std::shared_ptr<const SonarGrid> grid = sonar_grid(s);
    const double bin_m = grid->bin_m, beam_rad = grid->narrowest_beam_rad();
    const double need =
        std::max(2 * norm(s.velocity_mps) * T / bin_m, 2 * deg2rad(norm(s.angular_rate_dps)) * T / beam_rad);
    return std::clamp(int(std::ceil(need)), 1, std::min(kMaxMotionSlabs, s.range_bins));
}

/// Rotation by the vector w [rad] (axis w / |w|, angle |w|): Rodrigues' formula.
glm::dmat3 rotation_by(const glm::dvec3& w) {
    const double a = glm::length(w);
    if (a == 0) return glm::dmat3(1.0);
    const glm::dvec3 k = w / a;
    glm::dmat3 K(0.0); // column-major: K[col][row], K v = k x v
    K[1][0] = -k.z, K[2][0] = k.y;
    K[0][1] = k.z, K[2][1] = -k.x;
    K[0][2] = -k.y, K[1][2] = k.x;
    return glm::dmat3(1.0) + std::sin(a) * K + (1 - std::cos(a)) * (K * K);
}

} // namespace

bool moving(const SonarParams& s) {
    return norm(s.velocity_mps) > 0 || norm(s.angular_rate_dps) > 0;
}

double ping_interval_s(const SonarParams& s, double c) {
    return 2 * s.range_max_m / c + 420e-6;
}

int ping_of_beam(const SonarParams& s, int beam) {
    return (s.beams - 1 - beam) % s.pings_per_frame;
}

Pose pose_at(const SonarParams& s, double t) {
    if (t == 0 || !moving(s)) return s.pose;
    const glm::dmat3 R0 = rotation_matrix(s.pose.orientation_deg);
    const glm::dmat3 R =
        R0 * rotation_by(glm::dvec3(deg2rad(s.angular_rate_dps[0]), deg2rad(s.angular_rate_dps[1]),
                                    deg2rad(s.angular_rate_dps[2])) *
                         t);
    const glm::dvec3 p = to_glm(s.pose.position_m) + R0 * (to_glm(s.velocity_mps) * t);
    Pose out;
    out.position_m = {p.x, p.y, p.z};
    out.orientation_deg = orientation_of(R);
    return out;
}

std::vector<AcquisitionSlot> acquisition_slots(const SonarParams& s, double c) {
    const bool move = moving(s);
    const int P = move ? s.pings_per_frame : 1, S = slabs(s, c), K = s.range_bins;
    const std::shared_ptr<const SonarGrid> grid = sonar_grid(s);
    std::vector<AcquisitionSlot> out;
    for (int k = 0; k < P; ++k)
        for (int j = 0; j < S; ++j) {
            AcquisitionSlot a;
            a.ping = k;
            a.bin_begin = int(std::lround(double(j) * K / S));
            a.bin_end = int(std::lround(double(j + 1) * K / S));
            a.t_tx_s = move ? k * ping_interval_s(s, c) : 0;
            const double r_mid = grid->range_at_bin_m(0.5 * (a.bin_begin + a.bin_end));
            a.t_rx_s = move ? a.t_tx_s + 2 * r_mid / c : 0;
            out.push_back(a);
        }
    return out;
}

SlabPoseChange slab_pose_change(const SonarParams& s, double c) {
    const double half = window_s(s, c) / slabs(s, c) / 2;
    return {norm(s.angular_rate_dps) * half, norm(s.velocity_mps) * half};
}

} // namespace sonarsim

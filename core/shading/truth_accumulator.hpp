// One (range bin, beam) cell's ground-truth sums over the contributions echoing into it (accumulate.cpp).
#pragma once
#include "core/data/pose.hpp"
#include "core/shading/ground_truth.hpp"

#include <array>
#include <bitset>
#include <cmath>
#include <cstdint>
#include <limits>
#include <tuple>
#include <utility>

namespace sonarsim {

struct TruthAccumulator {
    double w = 0, e = 0, inc = 0, range = 0;
    double e_min = std::numeric_limits<double>::infinity(), e_max = -e_min;
    glm::dvec3 p{0};
    std::bitset<64>
        materials; ///< the floor and objects 0 ... 61 a bit each, later objects 62, the surface 63
    /// Echo per surface (key: bounces << 32 | material index), for the strongest one; a ninth surface in one
    /// cell is not counted there (it still counts in `materials`).
    std::array<std::pair<std::uint64_t, double>, 8> share{};
    int shares = 0;

    /// A contribution of echo v at elevation e [rad], incidence inc [deg], world point `point` at
    /// `range_m` from the sonar.
    void add(double v, double e_rad, double inc_deg, const glm::dvec3& point, double range_m,
             std::uint64_t key, unsigned bit) {
        w += v, e += v * e_rad, inc += v * inc_deg, range += v * range_m;
        e_min = std::min(e_min, e_rad), e_max = std::max(e_max, e_rad);
        p += v * point;
        add_share(key, v);
        materials.set(bit);
    }
    void add_share(std::uint64_t m, double v) {
        for (int n = 0; n < shares; ++n)
            if (share[size_t(n)].first == m) {
                share[size_t(n)].second += v;
                return;
            }
        if (shares < int(share.size())) share[size_t(shares++)] = {m, v};
    }
    /// The strongest (material index as a signed id, bounces); (-1, 0) when none.
    std::pair<std::int32_t, std::int32_t> strongest() const {
        int best = 0;
        for (int n = 1; n < shares; ++n)
            if (share[size_t(n)].second > share[size_t(best)].second) best = n;
        if (!shares) return {-1, 0};
        const std::uint64_t key = share[size_t(best)].first;
        return {std::int32_t(std::uint32_t(key & 0xFFFFFFFFu)), std::int32_t(key >> 32)};
    }
    /// Writes the means into cell `at` of `gt` (nothing where nothing echoed).
    void write(GroundTruth& gt, size_t at) const {
        if (!(w > 0)) return;
        gt.elevation_deg[at] = float(rad2deg(e / w));
        gt.elevation_min_deg[at] = float(rad2deg(e_min));
        gt.elevation_max_deg[at] = float(rad2deg(e_max));
        for (int axis = 0; axis < 3; ++axis) gt.point_m[at * 3 + axis] = float(p[axis] / w);
        gt.range_m[at] = float(range / w);
        std::tie(gt.object_id[at], gt.bounces[at]) = strongest(); // 0 the floor, i + 1 objects[i]
        gt.incidence_deg[at] = float(inc / w);
        gt.surfaces[at] = std::int32_t(materials.count());
    }
};

} // namespace sonarsim

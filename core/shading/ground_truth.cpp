#include "core/shading/ground_truth.hpp"

#include "core/shading/footprint.hpp"
#include "core/geometry/geometry.hpp"
#include "core/shading/physics.hpp"
#include "core/base/pose.hpp"
#include "core/shading/shade.hpp"

#include <array>
#include <bitset>
#include <cmath>
#include <limits>
#include <tuple>
#include <tbb/parallel_for.h>

namespace sonarsim {
namespace {

/// One (bin, beam) cell's sums over its contributions.
struct Accumulator {
    double w = 0, e = 0, inc = 0;
    double e_min = std::numeric_limits<double>::infinity(), e_max = -e_min;
    glm::dvec3 p{0};
    std::bitset<64>
        materials; ///< the floor and objects 0 ... 61 a bit each, later objects 62, the surface 63
    /// Echo per surface (material index), for the strongest one; a ninth surface in one cell is not counted
    /// there (it still counts in `materials`).
    std::array<std::pair<std::uint64_t, double>, 8> share{}; ///< key: bounces << 32 | material index
    int shares = 0;
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
};

} // namespace

const std::vector<std::string>& ground_truth_names() {
    static const std::vector<std::string> names = {
        "elevation_deg", "elevation_min_deg", "elevation_max_deg", "point_m",
        "object_id",     "incidence_deg",     "surfaces",          "bounces"};
    return names;
}

GroundTruth compute_ground_truth(const TraceResult& hits, const SceneDesc& s) {
    const ShadeConstants k = shade_constants(s);
    const int K = s.sonar.range_bins, N = s.sonar.beams;
    const double r_min = s.sonar.range_min_m, r_max = s.sonar.range_max_m, dr = (r_max - r_min) / K;
    const bool spread = s.sampling.binning == EchoBinning::Footprint;
    const glm::dmat3 R = rotation_matrix(s.sonar.pose.orientation_deg);
    const glm::dvec3 origin = to_glm(s.sonar.pose.position_m);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const size_t cells = size_t(K) * size_t(N);

    GroundTruth gt;
    gt.bins = K, gt.beams = N;
    for (auto* v : {&gt.elevation_deg, &gt.elevation_min_deg, &gt.elevation_max_deg, &gt.incidence_deg})
        v->assign(cells, nan);
    gt.point_m.assign(cells * 3, nan);
    gt.object_id.assign(cells, -1);
    gt.surfaces.assign(cells, 0);
    gt.bounces.assign(cells, 0);
    tbb::parallel_for(0, std::min(N, hits.beams), [&](int i) {
        const BeamContributions beam_cells(hits, i);
        // Levels as shade() computes them, then weights relative to the beam's strongest cell.
        std::vector<double> x;
        const double x_max = contribution_levels(beam_cells, s, k, x);
        if (!std::isfinite(x_max)) return;
        std::vector<Accumulator> acc(static_cast<size_t>(K));
        for (size_t n = 0; n < beam_cells.size(); ++n) {
            const Cell& c = beam_cells[n];
            const GhostCell* ghost = beam_cells.ghost(n);
            const std::uint64_t key = std::uint64_t(ghost ? ghost->order() : 0) << 32 | c.material;
            const unsigned bit = c.material == kSurfaceMaterial ? 63u : std::min(c.material, 62u);
            const double w = std::exp(x[n] - x_max);
            if (!(w > 0)) continue;
            const double inc = rad2deg(std::acos(std::clamp(double(c.cos_incidence), 0.0, 1.0)));
            detail::for_each_bin(c, spread, K, r_min, r_max, dr, [&](int b, double frac) {
                const double v = w * frac;
                if (!(v > 0)) return;
                const double r = r_min + (b + 0.5) * dr, e = detail::elevation_at(c, r);
                Accumulator& a = acc[size_t(b)];
                a.w += v, a.e += v * e, a.inc += v * inc;
                a.e_min = std::min(a.e_min, e), a.e_max = std::max(a.e_max, e);
                a.p +=
                    v * (ghost ? glm::dvec3(c.point) : origin + r * (R * sonar_direction(c.azimuth_rad, e)));
                a.add_share(key, v);
                a.materials.set(bit);
            });
        }
        for (int b = 0; b < K; ++b) {
            const Accumulator& a = acc[size_t(b)];
            if (!(a.w > 0)) continue;
            const size_t at = size_t(b) * N + i;
            gt.elevation_deg[at] = float(rad2deg(a.e / a.w));
            gt.elevation_min_deg[at] = float(rad2deg(a.e_min));
            gt.elevation_max_deg[at] = float(rad2deg(a.e_max));
            for (int axis = 0; axis < 3; ++axis) gt.point_m[at * 3 + axis] = float(a.p[axis] / a.w);
            std::tie(gt.object_id[at], gt.bounces[at]) = a.strongest(); // 0 the floor, i + 1 objects[i]
            gt.incidence_deg[at] = float(a.inc / a.w);
            gt.surfaces[at] = std::int32_t(a.materials.count());
        }
    });
    return gt;
}

EchoPath strongest_path(const TraceResult& hits, const SceneDesc& s, int bin, int beam) {
    EchoPath out;
    const int K = s.sonar.range_bins;
    if (beam < 0 || beam >= std::min(s.sonar.beams, hits.beams) || bin < 0 || bin >= K) return out;
    const double r_min = s.sonar.range_min_m, r_max = s.sonar.range_max_m, dr = (r_max - r_min) / K;
    const bool spread = s.sampling.binning == EchoBinning::Footprint;
    const BeamContributions cells(hits, beam);
    std::vector<double> x;
    if (!std::isfinite(contribution_levels(cells, s, shade_constants(s), x))) return out;
    double best = -std::numeric_limits<double>::infinity();
    size_t best_n = cells.size();
    for (size_t n = 0; n < cells.size(); ++n) {
        if (!std::isfinite(x[n])) continue;
        detail::for_each_bin(cells[n], spread, K, r_min, r_max, dr, [&](int b, double frac) {
            if (b == bin && frac > 0 && x[n] + std::log(frac) > best)
                best = x[n] + std::log(frac), best_n = n;
        });
    }
    if (best_n == cells.size()) return out;
    const Cell& c = cells[best_n];
    const GhostCell* g = cells.ghost(best_n);
    auto add = [&](const glm::vec3& p) { out.points_m.push_back({double(p.x), double(p.y), double(p.z)}); };
    const auto& o = s.sonar.pose.position_m;
    out.points_m.push_back(o);
    for (int k = 0; g && k < g->tx_bounces; ++k) add(g->mirror_point[k]);
    add(c.point);
    for (int k = g ? g->rx_bounces - 1 : -1; k >= 0; --k) add(g->mirror_point[k]);
    out.points_m.push_back(o);
    out.bounces = g ? g->order() : 0;
    out.out_bounces = g ? g->tx_bounces : 0;
    out.object_id = std::int32_t(c.material);
    return out;
}

std::vector<std::pair<std::string, Bytes>> ground_truth_files(const std::string& prefix,
                                                              const GroundTruth& gt) {
    const std::vector<std::size_t> shape{std::size_t(gt.bins), std::size_t(gt.beams)};
    auto f32 = [&](const std::vector<float>& v, std::vector<std::size_t> sh) {
        return encode_npy_array(v.data(), v.size() * 4, "<f4", sh);
    };
    auto i32 = [&](const std::vector<std::int32_t>& v) {
        return encode_npy_array(v.data(), v.size() * 4, "<i4", shape);
    };
    const std::string p = prefix + "_gt_";
    return {{p + "elevation_deg.npy", f32(gt.elevation_deg, shape)},
            {p + "elevation_min_deg.npy", f32(gt.elevation_min_deg, shape)},
            {p + "elevation_max_deg.npy", f32(gt.elevation_max_deg, shape)},
            {p + "point_m.npy", f32(gt.point_m, {shape[0], shape[1], 3})},
            {p + "object_id.npy", i32(gt.object_id)},
            {p + "incidence_deg.npy", f32(gt.incidence_deg, shape)},
            {p + "surfaces.npy", i32(gt.surfaces)},
            {p + "bounces.npy", i32(gt.bounces)}};
}

} // namespace sonarsim

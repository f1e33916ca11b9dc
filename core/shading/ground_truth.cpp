#include "core/shading/ground_truth.hpp"

#include "core/shading/footprint.hpp"
#include "core/geometry/geometry.hpp"
#include "core/shading/physics.hpp"
#include "core/base/pose.hpp"
#include "core/shading/shade.hpp"

#include <cmath>
#include <limits>

namespace sonarsim {
const std::vector<std::string>& ground_truth_names() {
    static const std::vector<std::string> names = {
        "elevation_deg", "elevation_min_deg", "elevation_max_deg", "point_m",
        "object_id",     "incidence_deg",     "surfaces",          "bounces"};
    return names;
}

GroundTruth empty_ground_truth(int bins, int beams) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const size_t cells = size_t(bins) * size_t(beams);
    GroundTruth gt;
    gt.bins = bins, gt.beams = beams;
    for (auto* v : {&gt.elevation_deg, &gt.elevation_min_deg, &gt.elevation_max_deg, &gt.incidence_deg})
        v->assign(cells, nan);
    gt.point_m.assign(cells * 3, nan);
    gt.object_id.assign(cells, -1);
    gt.surfaces.assign(cells, 0);
    gt.bounces.assign(cells, 0);
    return gt;
}

EchoPath echo_path(const TraceResult& hits, const SceneDesc& s, int beam, std::int32_t contribution) {
    EchoPath out;
    if (contribution < 0 || beam < 0 || beam >= hits.beams) return out;
    const BeamContributions cells(hits, beam);
    if (size_t(contribution) >= cells.size()) return out;
    const size_t best_n = size_t(contribution);
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

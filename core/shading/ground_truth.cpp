#include "core/shading/ground_truth.hpp"

#include "core/shading/footprint.hpp"
#include "core/geometry/geometry.hpp"
#include "core/shading/physics.hpp"
#include "core/data/pose.hpp"
#include "core/shading/shade.hpp"

#include <cmath>
#include <limits>

namespace sonarsim {
const std::vector<GroundTruthField>& ground_truth_fields() {
    using G = GroundTruth;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    static const std::vector<GroundTruthField> fields = {
        {"elevation_deg", &G::elevation_deg, nullptr, 1, nan},
        {"elevation_min_deg", &G::elevation_min_deg, nullptr, 1, nan},
        {"elevation_max_deg", &G::elevation_max_deg, nullptr, 1, nan},
        {"point_m", &G::point_m, nullptr, 3, nan},
        {"range_m", &G::range_m, nullptr, 1, nan},
        {"object_id", nullptr, &G::object_id, 1, -1},
        {"incidence_deg", &G::incidence_deg, nullptr, 1, nan},
        {"surfaces", nullptr, &G::surfaces, 1, 0},
        {"bounces", nullptr, &G::bounces, 1, 0},
    };
    return fields;
}

const std::vector<std::string>& ground_truth_names() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> out;
        for (const GroundTruthField& f : ground_truth_fields()) out.push_back(f.name);
        return out;
    }();
    return names;
}

GroundTruth empty_ground_truth(int bins, int beams) {
    const size_t cells = size_t(bins) * size_t(beams);
    GroundTruth gt;
    gt.bins = bins, gt.beams = beams;
    for (const GroundTruthField& f : ground_truth_fields()) {
        const size_t n = cells * size_t(f.components);
        if (f.f32) (gt.*f.f32).assign(n, f.empty);
        if (f.i32) (gt.*f.i32).assign(n, std::int32_t(f.empty));
    }
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
    for (int k = 0; g && k < g->tx_bounces; ++k) add(g->mirror_point_m[k]);
    add(c.point_m);
    for (int k = g ? g->rx_bounces - 1 : -1; k >= 0; --k) add(g->mirror_point_m[k]);
    out.points_m.push_back(o);
    out.bounces = g ? g->order() : 0;
    out.out_bounces = g ? g->tx_bounces : 0;
    out.object_id = std::int32_t(c.material);
    return out;
}

} // namespace sonarsim

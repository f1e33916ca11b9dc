// Ground truth per (range bin, beam) against closed forms: on a flat floor the elevation behind each pixel
// follows from its range, azimuth and the pose; the point lies on the floor at the pixel's range and azimuth;
// the prism's pixels carry its object id.
#include "support.hpp"

#include "core/io/ground_truth_files.hpp"
#include "core/shading/ground_truth.hpp"
#include "core/data/pose.hpp"
#include "core/scene/scene_io.hpp"
#include "core/pipeline/simulator.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

using namespace sonarsim;

namespace {

/// Elevation [rad] at which azimuth a meets the floor z = 0 at range r, for the scene's pose (the root in
/// [-pi/2, pi/2] that points down); NaN when it does not.
double floor_elevation(const SceneDesc& s, double a, double r) {
    const glm::dmat3 R = rotation_matrix(s.sonar.pose.orientation_deg);
    // World z of the direction (cos e cos a, cos e sin a, sin e): A cos e + B sin e = C cos(e - delta).
    const double A = R[0][2] * std::cos(a) + R[1][2] * std::sin(a), B = R[2][2];
    const double C = std::hypot(A, B), delta = std::atan2(B, A);
    const double want = -s.sonar.pose.position_m[2] / r; // d_z that reaches z = 0 at range r
    if (std::abs(want) > C) return std::nan("");
    const double e = delta - std::acos(want / C);
    return std::abs(e) <= kPi / 2 ? e : delta + std::acos(want / C);
}

} // namespace

TEST_CASE("flat floor: each pixel's elevation and point follow from its range azimuth and the pose",
          "[ground_truth]") {
    SceneDesc s = default_scene();
    s.objects.clear();
    const auto frame = Simulator(s).render();
    const GroundTruth gt = compute_ground_truth(frame->hits(), s);
    const int K = s.sonar.range_bins, N = s.sonar.beams;
    REQUIRE(gt.bins == K);
    REQUIRE(gt.beams == N);
    const double dr = (s.sonar.range_max_m - s.sonar.range_min_m) / K;
    const double da = deg2rad(s.sonar.azimuth_fov_deg) / N;
    const glm::dvec3 o = to_glm(s.sonar.pose.position_m);
    int checked = 0;
    for (int k = 0; k < K; ++k)
        for (int i = 0; i < N; ++i) {
            const size_t at = size_t(k) * N + i;
            const bool echo = std::isfinite(frame->ideal().at(k, i));
            REQUIRE((gt.object_id[at] == 0) == echo); // the floor, exactly where something echoes
            if (!echo) continue;
            const double r = s.sonar.range_min_m + (k + 0.5) * dr;
            const double a = deg2rad(s.sonar.azimuth_fov_deg / 2) - (i + 0.5) * da;
            // The bin's own elevation span: the floor's elevation over its range and azimuth extent.
            double lo = 1e9, hi = -1e9;
            for (double rr : {r - dr / 2, r, r + dr / 2})
                for (double aa : {a - da / 2, a, a + da / 2}) {
                    const double e = floor_elevation(s, aa, rr);
                    if (std::isfinite(e)) lo = std::min(lo, e), hi = std::max(hi, e);
                }
            const double expect = floor_elevation(s, a, r);
            if (!std::isfinite(expect)) continue;
            INFO("bin " << k << " beam " << i);
            CHECK(std::abs(deg2rad(gt.elevation_deg[at]) - expect) <= (hi - lo) + 1e-6);
            CHECK(gt.elevation_min_deg[at] <= gt.elevation_deg[at] + 1e-4f);
            CHECK(gt.elevation_max_deg[at] >= gt.elevation_deg[at] - 1e-4f);
            const glm::dvec3 p(gt.point_m[at * 3], gt.point_m[at * 3 + 1], gt.point_m[at * 3 + 2]);
            CHECK(std::abs(p.z) <= r * (hi - lo) + 1e-4); // on the floor, within the bin's span
            CHECK(std::abs(glm::length(p - o) - r) < dr); // at the pixel's range
            const Polar q = world_to_sonar_polar(s.sonar.pose, p);
            CHECK(std::abs(deg2rad(q.azimuth_deg) - a) <= da / 2 + 1e-6); // and azimuth
            CHECK(gt.surfaces[at] == 1);
            CHECK(gt.incidence_deg[at] > 0);
            ++checked;
        }
    CHECK(checked > 10000);
}

TEST_CASE("the prism's pixels carry its object id", "[ground_truth]") {
    const SceneDesc s = default_scene();
    const auto frame = Simulator(s).render();
    const GroundTruth gt = compute_ground_truth(frame->hits(), s);
    // Where the prism brightens the image by 3 dB or more over the bare floor, it is the strongest
    // contributor.
    SceneDesc bare = s;
    bare.objects.clear();
    const auto floor_only = Simulator(bare).render();
    long brightened = 0;
    for (size_t at = 0; at < gt.object_id.size(); ++at)
        if (frame->ideal().level_db[at] > floor_only->ideal().level_db[at] + 6) {
            CHECK(gt.object_id[at] == 1);
            ++brightened;
        }
    CHECK(brightened > 50);
    // Its pixels lie within the prism's range from the sonar; some see the prism and the floor together.
    const glm::dvec3 o = to_glm(s.sonar.pose.position_m), c(1.5, 1.5, 0.11);
    const double dr = (s.sonar.range_max_m - s.sonar.range_min_m) / s.sonar.range_bins;
    for (size_t at = 0; at < gt.object_id.size(); ++at)
        if (gt.object_id[at] == 1) {
            const double r = s.sonar.range_min_m + (double(at / size_t(s.sonar.beams)) + 0.5) * dr;
            CHECK(std::abs(r - glm::length(c - o)) < 0.16); // half the prism's diagonal, 0.13 m, plus bins
        }
    CHECK(std::count(gt.surfaces.begin(), gt.surfaces.end(), 2) > 0);
}

TEST_CASE("ground truth files have the image's shape", "[ground_truth]") {
    GroundTruth gt;
    gt.bins = 2, gt.beams = 3;
    for (auto* v : {&gt.elevation_deg, &gt.elevation_min_deg, &gt.elevation_max_deg, &gt.incidence_deg})
        v->assign(6, 1.0f);
    gt.point_m.assign(18, 2.0f), gt.object_id.assign(6, 1), gt.surfaces.assign(6, 1), gt.bounces.assign(6, 0);
    const auto files = ground_truth_files("x", gt);
    REQUIRE(files.size() == ground_truth_names().size());
    for (size_t n = 0; n < files.size(); ++n) {
        CHECK(files[n].first == "x_gt_" + ground_truth_names()[n] + ".npy");
        const std::string header(files[n].second.begin() + 10, files[n].second.begin() + 80);
        const bool point = ground_truth_names()[n] == "point_m";
        CHECK(header.find(point ? "'shape': (2, 3, 3)" : "'shape': (2, 3)") != std::string::npos);
        const bool integer = ground_truth_names()[n] == "object_id" ||
                             ground_truth_names()[n] == "surfaces" || ground_truth_names()[n] == "bounces";
        CHECK(header.find(integer ? "'<i4'" : "'<f4'") != std::string::npos);
    }
}

// The streamed reference of `sonarsim study` and the benchmark: a scene traced a chunk of beams at a time
// must give the same image as the whole scene traced at once.
#include "core/data/pose.hpp"
#include "core/scene/sampling_scheme.hpp"
#include "core/scene/scene_io.hpp"
#include "core/shading/accumulate.hpp"
#include "core/analysis/study.hpp"
#include "core/sampling/trace.hpp"

#include "core/grid/sonar_grid.hpp"
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>

using namespace sonarsim;

namespace {

double max_abs_diff(const glm::dmat3& a, const glm::dmat3& b) {
    double d = 0;
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) d = std::max(d, std::abs(a[c][r] - b[c][r]));
    return d;
}

PolarImage whole(const SceneGeometry& g, SceneDesc s, const Sampling& m) {
    set_scheme(s.sampling, m.scheme);
    s.sampling.elevation_rays = m.elevation_rays;
    s.sampling.azimuth_rays = m.azimuth_rays;
    return shade(trace(g, s), s);
}

double max_db_diff(const PolarImage& a, const PolarImage& b) {
    double d = 0;
    for (size_t n = 0; n < a.level_db.size(); ++n)
        if (std::isfinite(a.level_db[n]) && std::isfinite(b.level_db[n]))
            d = std::max(d, double(std::abs(a.level_db[n] - b.level_db[n])));
    return d;
}

} // namespace

TEST_CASE("orientation_deg_of inverts rotation_matrix, also at and near pitch +-90 deg", "[study][pose]") {
    for (double roll : {-170.0, -30.0, 0.0, 12.5, 90.0, 179.0})
        for (double pitch : {-90.0, -89.9999, -45.0, 0.0, 29.79, 60.0, 89.99999, 90.0})
            for (double yaw : {-179.0, -38.96, 0.0, 45.0, 135.0}) {
                const glm::dmat3 R = rotation_matrix({roll, pitch, yaw});
                const glm::dmat3 back = rotation_matrix(orientation_deg_of(R));
                INFO("roll " << roll << " pitch " << std::to_string(pitch) << " yaw " << yaw);
                CHECK(max_abs_diff(R, back) < 1e-9);
            }
}

TEST_CASE("a beam sub-scene's beams point exactly where the full scene's beams do", "[study][pose]") {
    SceneDesc s = default_scene();
    s.sonar.beams = 10;
    const std::vector<double> full = sonar_grid(s.sonar)->beam_azimuths_deg();
    const glm::dmat3 R = rotation_matrix(s.sonar.pose.orientation_deg);
    for (auto [first, last] : {std::pair{0, 3}, std::pair{3, 7}, std::pair{7, 10}, std::pair{4, 5}}) {
        const SceneDesc sub = beam_subscene(s, first, last);
        const std::vector<double> part = sonar_grid(sub.sonar)->beam_azimuths_deg();
        const glm::dmat3 Rs = rotation_matrix(sub.sonar.pose.orientation_deg);
        for (int j = 0; j < last - first; ++j)
            for (double e : {-0.1, 0.0, 0.05}) {
                const glm::dvec3 a = R * sonar_direction(deg2rad(full[size_t(first + j)]), e);
                const glm::dvec3 b = Rs * sonar_direction(deg2rad(part[size_t(j)]), e);
                CHECK(glm::length(a - b) < 1e-12);
            }
    }
}

TEST_CASE("the chunked (streamed) render equals the whole render on the Fig. 9 scene", "[study][accuracy]") {
    SceneDesc s = default_scene();
    const SceneGeometry g(s);
    for (const Sampling m :
         {Sampling{SamplingScheme::Spread, 243, 3}, Sampling{SamplingScheme::Uniform, 281, 1}})
        for (int per_chunk : {1, 7, 50}) {
            std::uint64_t rays = 0;
            const PolarImage chunked = render_in_chunks(g, s, m, per_chunk, {}, &rays);
            const PolarImage ref = whole(g, s, m);
            const ImageError e = compare_images(chunked, ref);
            std::printf("%s, %d beams per chunk: rel L1 %.2e, max |dB| %.2e, holes %ld, spurious %ld\n",
                        m.label().c_str(), per_chunk, e.rel_l1, max_db_diff(chunked, ref), e.holes,
                        e.spurious);
            CHECK(rays == std::uint64_t(s.sonar.beams) * m.elevation_rays * m.azimuth_rays);
            CHECK(e.rel_l1 < 1e-5);
            CHECK(max_db_diff(chunked, ref) < 1e-3);
            CHECK(e.holes == 0);
            CHECK(e.spurious == 0);
            CHECK(e.echoing_ref > 1000);
        }
}

TEST_CASE("the chunked render equals the whole render looking straight down (pitch 90 deg)",
          "[study][accuracy]") {
    SceneDesc s = default_scene();
    s.sonar.pose.orientation_deg = {0, 90, 30};
    s.sonar.pose.position_m = {1.5, 1.5, 2.0};
    const SceneGeometry g(s);
    const Sampling m{SamplingScheme::Spread, 101, 3};
    const ImageError e = compare_images(render_in_chunks(g, s, m, 9), whole(g, s, m));
    CHECK(e.rel_l1 < 1e-5);
    CHECK(e.holes == 0);
    CHECK(e.spurious == 0);
    CHECK(e.echoing_ref > 100);
}

TEST_CASE("the streamed reference bounds its chunks by kChunkCells", "[study]") {
    SceneDesc s = default_scene();
    s.sonar.beams = 4, s.sonar.range_bins = 64;
    const SceneGeometry g(s);
    int calls = 0;
    double last = 0;
    // 60000 x 18 rays per beam = 1.08e6 cells per beam > kChunkCells: one beam per chunk.
    render_in_chunks(g, s, {SamplingScheme::Spread, 60000, 18}, 0, [&](double f) {
        ++calls;
        CHECK(f > last);
        last = f;
    });
    CHECK(calls == 4);
    CHECK(last == 1.0);
}

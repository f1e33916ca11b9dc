#include "core/analysis/study.hpp"

#include "core/shading/estimate.hpp"

#include "core/base/errors.hpp"
#include "core/data/pose.hpp"
#include "core/grid/beam_tables.hpp"
#include "core/shading/accumulate.hpp"
#include "core/base/timing.hpp"
#include "core/sampling/trace.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

namespace sonarsim {
namespace {

SceneDesc with_sampling(SceneDesc s, const Sampling& m) {
    set_scheme(s.sampling, m.scheme);
    s.sampling.elevation_rays = m.elevation_rays;
    s.sampling.azimuth_rays = m.azimuth_rays;
    return s;
}

PolarImage render_raw(const SceneGeometry& g, const SceneDesc& s, TraceResult* hits = nullptr) {
    ImagePass whole;
    TraceResult t = trace(g, s, {}, &whole);
    const auto shaded = whole.take();
    PolarImage img = shaded ? *shaded->image : shade(t, s);
    if (t.halves) t.error_estimate = estimate_error(t, s);
    if (hits) *hits = std::move(t);
    return img;
}

} // namespace

std::string Sampling::label() const {
    return std::string(scheme_name(scheme)) + " " + std::to_string(elevation_rays) + "x" +
           std::to_string(azimuth_rays);
}

Vec3d orientation_deg_of(const glm::dmat3& m) {
    // glm is column-major: R_rc = m[c][r]. With R = Rz(y) Ry(p) Rx(r): R00 = cos p cos y, R10 = cos p sin y,
    // so yaw first (any value at pitch +-90 deg, where only yaw -+ roll is defined); then
    // Rz(-y) R = Ry(p) Rx(r), whose rows give roll and pitch from entries of size 1, which keeps them
    // precise near pitch +-90 deg (the textbook atan2(R21, R22) loses digits as cos p -> 0).
    const double yaw = std::atan2(m[0][1], m[0][0]);
    const double cy = std::cos(yaw), sy = std::sin(yaw);
    const double roll = std::atan2(sy * m[2][0] - cy * m[2][1], cy * m[1][1] - sy * m[1][0]);
    const double pitch = std::atan2(-m[0][2], cy * m[0][0] + sy * m[0][1]);
    return {rad2deg(roll), rad2deg(pitch), rad2deg(yaw)};
}

SceneDesc beam_subscene(const SceneDesc& scene, int first, int last) {
    const int N = scene.sonar.beams;
    if (first < 0 || last > N || first >= last) throw std::invalid_argument("beam_subscene: bad beam range");
    if (scene.sonar.beam_table != kUniformBeams)
        throw InputError(
            scene.source_file, "sonar.beam_table",
            "the dense reference renders the fan in chunks of evenly spaced beams; allowed here: " +
                std::string(kUniformBeams));
    const double theta = scene.sonar.azimuth_fov_deg;
    // Beam i sits at a_i = Theta/2 - (i + 1/2) Theta/N; the chunk's beams j = i - first at a_c + a'_j with
    // a'_j = Theta'/2 - (j + 1/2) Theta'/N', Theta' = Theta (last - first)/N, N' = last - first.
    const double a_c = deg2rad(theta / 2 - 0.5 * (first + last) * theta / N);
    // Directions are R (cos e cos a, cos e sin a, sin e): rotating by Rz(a_c) first shifts the azimuth by
    // a_c.
    glm::dmat3 rz(1.0);
    rz[0][0] = std::cos(a_c), rz[0][1] = std::sin(a_c); // column 0
    rz[1][0] = -std::sin(a_c), rz[1][1] = std::cos(a_c);
    SceneDesc sub = scene;
    sub.sonar.beams = last - first;
    sub.sonar.azimuth_fov_deg = theta * (last - first) / N;
    sub.sonar.pose.orientation_deg =
        orientation_deg_of(rotation_matrix(scene.sonar.pose.orientation_deg) * rz);
    return sub;
}

PolarImage render_in_chunks(const SceneGeometry& g, const SceneDesc& scene, const Sampling& m, int per_chunk,
                            const Progress& progress, std::uint64_t* rays) {
    if (!placement_spec(kSamplingSchemes[size_t(m.scheme)].placement).chunks)
        throw std::invalid_argument("render_in_chunks: " + std::string(scheme_name(m.scheme)) +
                                    " sampling compares neighbouring beams");
    const SceneDesc s = with_sampling(scene, m);
    const int N = s.sonar.beams, K = s.sonar.range_bins;
    if (per_chunk <= 0) {
        const double cells_per_beam = double(m.elevation_rays) * m.azimuth_rays;
        per_chunk = int(std::clamp(double(kChunkCells) / cells_per_beam, 1.0, double(N)));
    }
    PolarImage out;
    out.bins = K, out.beams = N;
    out.level_db.assign(size_t(K) * size_t(N), -INFINITY);
    std::uint64_t traced = 0;
    for (int first = 0; first < N; first += per_chunk) {
        const int last = std::min(N, first + per_chunk);
        const SceneDesc sub = last - first == N ? s : beam_subscene(s, first, last);
        TraceResult t = trace(g, sub);
        traced += t.rays_traced;
        const PolarImage part = shade(t, sub);
        t = TraceResult{}; // release the chunk's cells before the next one is traced
        for (int b = 0; b < K; ++b)
            for (int j = 0; j < part.beams; ++j)
                out.level_db[size_t(b) * size_t(N) + size_t(first + j)] = part.at(b, j);
        if (progress) progress(double(last) / N);
    }
    if (rays) *rays = traced;
    return out;
}

StudyReference make_reference(const SceneGeometry& g, const SceneDesc& s, const Progress& progress,
                              const Sampling& d) {
    StudyReference ref;
    const auto t0 = std::chrono::steady_clock::now();
    if (has_floor_reference(s)) {
        ref.kind = "semi-analytic floor integral";
        ref.description =
            "Gauss-Legendre, 32 azimuth panels x 8 nodes per beam, elevation split at bin-edge roots";
        ref.image = floor_reference(s, 32);
        ref.time_ms = ms_since(t0);
        ref.convergence = compare_images(floor_reference(s, 8), ref.image);
        if (progress) progress(1.0);
        return ref;
    }
    // Far denser than any ladder setting; true normals; its convergence is shown against a 3x coarser run.
    SceneDesc dense = s;
    dense.sampling.normals = NormalSource::Mesh;
    const Sampling c{SamplingScheme::Spread, std::max(1, d.elevation_rays / 3),
                     std::max(1, d.azimuth_rays / 3)};
    // Progress: the dense run costs (3 x 3) times the coarser one.
    const double share = 9.0 / 10.0;
    ref.kind = "dense spread run, streamed";
    ref.description =
        std::string(scheme_name(c.scheme)) + ", " + std::to_string(d.elevation_rays) + " x " +
        std::to_string(d.azimuth_rays) +
        " rays per beam, true normals, traced and shaded a chunk of beams at a time; convergence "
        "against " +
        std::to_string(c.elevation_rays) + " x " + std::to_string(c.azimuth_rays);
    ref.image = render_in_chunks(
        g, dense, d, 0,
        [&](double f) {
            if (progress) progress(share * f);
        },
        &ref.rays);
    ref.time_ms = ms_since(t0);
    const PolarImage coarser = render_in_chunks(g, dense, c, 0, [&](double f) {
        if (progress) progress(share + (1 - share) * f);
    });
    ref.convergence = compare_images(coarser, ref.image);
    return ref;
}

StudyRow measure(const SceneGeometry& g, const SceneDesc& scene, const Sampling& m, int repeats,
                 const PolarImage& reference) {
    const SceneDesc s = with_sampling(scene, m);
    StudyRow row;
    row.sampling = m;
    std::vector<double> times;
    PolarImage img;
    TraceResult hits;
    for (int r = 0; r < std::max(1, repeats); ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        img = render_raw(g, s, &hits);
        times.push_back(ms_since(t0));
    }
    std::sort(times.begin(), times.end());
    row.time_ms = times[times.size() / 2];
    row.rays = double(hits.rays_traced);
    row.estimate = hits.error_estimate;
    row.error = compare_images(img, reference);
    return row;
}

std::vector<Sampling> default_ladder(bool quick) {
    using S = SamplingScheme;
    std::vector<Sampling> v = {{S::Uniform, 281, 1},   {S::Uniform, 1000, 1},  {S::Uniform, 3000, 2},
                               {S::Uniform, 10000, 4}, {S::Spread, 31, 1},     {S::Spread, 101, 1},
                               {S::Spread, 281, 1},    {S::Spread, 1000, 2},   {S::Spread, 3000, 4},
                               {S::Adaptive, 11, 1},   {S::Adaptive, 31, 1},   {S::Adaptive, 101, 1},
                               {S::Adaptive, 281, 1},  {S::Adaptive, 1000, 2}, {S::Jittered, 25, 1},
                               {S::Jittered, 75, 1},   {S::Jittered, 250, 2}};
    if (quick)
        v.erase(std::remove_if(
                    v.begin(), v.end(),
                    [](const Sampling& m) { return double(m.elevation_rays) * m.azimuth_rays > 3000; }),
                v.end());
    return v;
}

} // namespace sonarsim

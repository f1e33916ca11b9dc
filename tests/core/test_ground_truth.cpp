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
#include <cstring>
#include <map>
#include <zlib.h>

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

/// A 16-bit gray PNG read back with zlib's inflate and the PNG specification's filters (none, Sub, Up,
/// Average, Paeth), independently of the encoder: its values row by row and its tEXt chunks.
struct Gray16 {
    int width = 0, height = 0;
    std::vector<std::uint16_t> v;
    std::map<std::string, std::string> text;
};
Gray16 read_gray16(const Bytes& b) {
    Gray16 out;
    REQUIRE(b.size() > 8);
    REQUIRE(std::memcmp(b.data(), "\x89PNG\r\n\x1a\n", 8) == 0);
    auto be32 = [&](size_t at) {
        return std::uint32_t(b[at]) << 24 | std::uint32_t(b[at + 1]) << 16 | std::uint32_t(b[at + 2]) << 8 |
               b[at + 3];
    };
    Bytes idat;
    for (size_t at = 8; at + 12 <= b.size();) {
        const size_t n = be32(at);
        const std::string type(b.begin() + long(at) + 4, b.begin() + long(at) + 8);
        const std::uint8_t* d = b.data() + at + 8;
        CHECK(std::uint32_t(::crc32(0, b.data() + at + 4, uInt(n + 4))) == be32(at + 8 + n));
        if (type == "IHDR") {
            out.width = int(be32(at + 8)), out.height = int(be32(at + 12));
            CHECK(int(d[8]) == 16); // bit depth
            CHECK(int(d[9]) == 0);  // gray
        } else if (type == "IDAT") {
            idat.insert(idat.end(), d, d + n);
        } else if (type == "tEXt") {
            const std::string t(d, d + n);
            out.text[t.substr(0, t.find('\0'))] = t.substr(t.find('\0') + 1);
        }
        at += 12 + n;
    }
    const size_t stride = size_t(out.width) * 2;
    std::vector<std::uint8_t> raw((stride + 1) * size_t(out.height));
    uLongf raw_n = uLongf(raw.size());
    REQUIRE(::uncompress(raw.data(), &raw_n, idat.data(), uLong(idat.size())) == Z_OK);
    REQUIRE(raw_n == raw.size());
    std::vector<std::uint8_t> prev(stride, 0), row(stride);
    for (int y = 0; y < out.height; ++y) {
        const std::uint8_t* in = raw.data() + size_t(y) * (stride + 1);
        for (size_t i = 0; i < stride; ++i) {
            const int a = i >= 2 ? row[i - 2] : 0, up = prev[i], c = i >= 2 ? prev[i - 2] : 0;
            const int p = a + up - c, pa = std::abs(p - a), pb = std::abs(p - up), pc = std::abs(p - c);
            const int pred = in[0] == 0   ? 0
                             : in[0] == 1 ? a
                             : in[0] == 2 ? up
                             : in[0] == 3 ? (a + up) / 2
                                          : (pa <= pb && pa <= pc ? a
                                             : pb <= pc           ? up
                                                                  : c);
            row[i] = std::uint8_t(in[1 + i] + pred);
        }
        for (int x = 0; x < out.width; ++x)
            out.v.push_back(std::uint16_t(row[2 * size_t(x)] << 8 | row[2 * size_t(x) + 1]));
        prev = row;
    }
    return out;
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

TEST_CASE("range_m: the bin's centre range for direct echoes, a ghost's scatterer nearer than it shows",
          "[ground_truth]") {
    SceneDesc s = load_scene(SONARSIM_ASSETS "/scenes/tank.json"); // walls and a surface as mirrors
    for (const int bounces : {0, 1}) {
        s.sampling.bounces = bounces;
        Simulator sim(s);
        sim.request({true, false});
        const GroundTruth& gt = *sim.render()->truth_ptr;
        const SonarGrid grid(s.sonar);
        int direct = 0, ghosts = 0;
        for (int k = 0; k < gt.bins; ++k)
            for (int b = 0; b < gt.beams; ++b) {
                const size_t c = size_t(k) * size_t(gt.beams) + size_t(b);
                INFO("bin " << k << ", beam " << b << ", bounces " << bounces);
                CHECK(std::isnan(gt.range_m[c]) == std::isnan(gt.elevation_deg[c]));
                if (std::isnan(gt.range_m[c])) continue;
                const double r = grid.bin_centre_m(k);
                if (bounces == 0) {
                    CHECK(gt.range_m[c] == Approx(r).epsilon(1e-6));
                    ++direct;
                } else if (gt.bounces[c] > 0 && gt.range_m[c] < r - 2 * grid.bin_m) {
                    ++ghosts;
                }
            }
        CHECK((bounces == 0 ? direct : ghosts) > 100);
    }
}

TEST_CASE("the ground truth's 16-bit PNG maps hold range_m and elevation_deg at their scale, laid out as the "
          "polar image",
          "[ground_truth]") {
    SceneDesc s = default_scene();
    Simulator sim(s);
    sim.request({true, false});
    const GroundTruth& gt = *sim.render()->truth_ptr;
    const auto files = ground_truth_map_files("x", gt, s);
    const auto maps = ground_truth_maps(s);
    REQUIRE(files.size() == 2);
    const json meta = ground_truth_maps_metadata(s)["ground_truth_maps"];
    // Text PNG does not allow is refused, not written.
    CHECK_THROWS_AS(encode_png_gray16(1, 1, {1}, {{" lead", "x"}}), std::invalid_argument);
    CHECK_THROWS_AS(encode_png_gray16(1, 1, {1}, {{"k", std::string("a\x01b")}}), std::invalid_argument);
    CHECK_THROWS_AS(encode_png_gray16(2, 1, {1}, {}), std::invalid_argument);
    for (size_t n = 0; n < files.size(); ++n) {
        const GroundTruthMap& m = maps[n];
        CHECK(files[n].first == "x_gt_" + m.name + ".png");
        const Gray16 png = read_gray16(files[n].second);
        REQUIRE(png.width == gt.beams);
        REQUIRE(png.height == gt.bins);
        // The scale as the metadata and the PNG's text say it, read back to the same doubles.
        CHECK(meta[n]["scale"].get<double>() == m.scale);
        CHECK(meta[n]["offset"].get<double>() == m.offset);
        CHECK(std::stod(png.text.at("sonarsim:scale")) == m.scale);
        CHECK(std::stod(png.text.at("sonarsim:offset")) == m.offset);
        const std::vector<float>& want = m.name == "range_m" ? gt.range_m : gt.elevation_deg; // by name
        int echoing = 0;
        for (int k = 0; k < gt.bins; ++k)
            for (int b = 0; b < gt.beams; ++b) {
                const std::uint16_t v =
                    png.v[size_t(gt.bins - 1 - k) * size_t(gt.beams) + size_t(b)]; // range up
                const float x = want[size_t(k) * size_t(gt.beams) + size_t(b)];
                INFO(m.name << " bin " << k << " beam " << b);
                if (std::isnan(x)) {
                    CHECK(v == 0);
                    continue;
                }
                REQUIRE(v > 0);
                CHECK(std::abs(m.offset + (v - 1) * m.scale - double(x)) <= 0.5 * m.scale * (1 + 1e-9));
                ++echoing;
            }
        CHECK(echoing > 1000);
    }
}

// Rendered images of the Fig. 9 scene: where the prism appears, and the golden image of the default scene.
#include "support.hpp"

#include "core/io/output.hpp"
#include "core/data/pose.hpp"
#include "core/scene/scene_io.hpp"
#include "core/pipeline/simulator.hpp"

#include <algorithm>
#include "core/grid/sonar_grid.hpp"
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>

using namespace sonarsim;
using namespace sonarsim::test;

namespace {

struct Echo {
    double azimuth_deg, range_m;
};

/// The prism's echoes in `scene`: the bins where a render without the floor echoes. Returns the azimuth and
/// range (bin centres) of the brightest of them in the full image, and the intensity-weighted centroid.
void prism_echo(const SceneDesc& scene, Echo& brightest, Echo& centroid) {
    SceneDesc bare = scene;
    bare.seafloor.reset();
    Simulator full(scene), prism(bare);
    const PolarImage& img = full.render()->polar();
    const PolarImage& only = prism.render()->polar();
    const std::vector<double> az = sonar_grid(scene.sonar)->beam_azimuths_deg(),
                              edges = sonar_grid(scene.sonar)->bin_edges_m();
    double best = -INFINITY, w = 0, wa = 0, wr = 0;
    for (int b = 0; b < img.bins; ++b)
        for (int i = 0; i < img.beams; ++i) {
            if (!std::isfinite(only.at(b, i))) continue;
            const double r = 0.5 * (edges[size_t(b)] + edges[size_t(b) + 1]), e = lin(only.at(b, i));
            if (img.at(b, i) > best) best = img.at(b, i), brightest = {az[size_t(i)], r};
            w += e, wa += e * az[size_t(i)], wr += e * r;
        }
    REQUIRE(w > 0);
    centroid = {wa / w, wr / w};
}

} // namespace

TEST_CASE("the prism's echo lands where the pose puts it (Fig. 9 poses 1 and 2)", "[render][pose]") {
    const SceneDesc pose1 = default_scene();
    const SceneDesc pose2 = load_scene(SONARSIM_ASSETS "/scenes/fig9_pose2.json");
    for (const SceneDesc* s : {&pose1, &pose2}) {
        const Polar expect = world_to_sonar_polar(s->sonar.pose, to_glm(s->objects[0].position_m));
        Echo top{}, mid{};
        prism_echo(*s, top, mid);
        std::printf("prism centre predicted at %+.2f deg, %.3f m; brightest echo %+.2f deg, %.3f m; centroid "
                    "%+.2f deg, %.3f m\n",
                    expect.azimuth_deg, expect.range_m, top.azimuth_deg, top.range_m, mid.azimuth_deg,
                    mid.range_m);
        // The prism's extent as the sonar sees it: its 8 corners' azimuths, its nearest and farthest points.
        const ObjectDesc& box = s->objects[0];
        REQUIRE(box.box_m);
        REQUIRE(box.orientation_deg == Vec3d{0, 0, 0});
        double az_lo = INFINITY, az_hi = -INFINITY, r_far = 0;
        glm::dvec3 nearest;
        for (int k = 0; k < 3; ++k)
            nearest[k] = std::clamp(s->sonar.pose.position_m[size_t(k)],
                                    box.position_m[size_t(k)] - (*box.box_m)[size_t(k)] / 2,
                                    box.position_m[size_t(k)] + (*box.box_m)[size_t(k)] / 2);
        for (int c = 0; c < 8; ++c) {
            glm::dvec3 p;
            for (int k = 0; k < 3; ++k)
                p[k] = box.position_m[size_t(k)] + ((c >> k & 1) ? 0.5 : -0.5) * (*box.box_m)[size_t(k)];
            const Polar q = world_to_sonar_polar(s->sonar.pose, p);
            az_lo = std::min(az_lo, q.azimuth_deg), az_hi = std::max(az_hi, q.azimuth_deg);
            r_far = std::max(r_far, q.range_m);
        }
        const double r_near = world_to_sonar_polar(s->sonar.pose, nearest).range_m;
        const double half_beam = s->sonar.azimuth_fov_deg / s->sonar.beams / 2;
        const double half_bin = (s->sonar.range_max_m - s->sonar.range_min_m) / s->sonar.range_bins / 2;
        INFO("predicted " << expect.azimuth_deg << " deg " << expect.range_m << " m; prism spans " << az_lo
                          << ".." << az_hi << " deg, " << r_near << ".." << r_far << " m");
        CHECK(top.azimuth_deg >= az_lo - half_beam);
        CHECK(top.azimuth_deg <= az_hi + half_beam);
        CHECK(top.range_m >= r_near - half_bin);
        CHECK(top.range_m <= r_far + half_bin);
        // The echo's intensity-weighted centre sits near the prism's centre (its faces facing the sonar pull
        // it a little closer).
        CHECK(mid.azimuth_deg == Approx(expect.azimuth_deg).margin(0.5));
        CHECK(mid.range_m == Approx(expect.range_m).margin(0.08));
        CHECK(mid.range_m < expect.range_m);
    }
}

// Golden image of the default scene at default settings.
// Tolerance: the finite masks (bins that echo) may differ in at most 0.1 % of the pixels; over bins finite in
// both, the median |dB difference| must be <= 0.05 dB and at most 0.1 % of the pixels may differ by more than
// 1 dB. On failure, SONARSIM_TEST_OUT gets golden_actual.npy, golden_actual.png (raw image as gray) and
// golden_diff.png (|diff| / 1 dB as gray; mask mismatches white).
// To accept a deliberate change (e.g. a new sampling scheme): run
//   SONARSIM_UPDATE_GOLDEN=1 build/tests/core/test_accuracy "[golden]"
// which rewrites tests/data/golden_default.npy and fails once to say so; commit the new file.
TEST_CASE("golden image of the default scene", "[render][golden]") {
    const SceneDesc s = default_scene();
    Simulator sim(s);
    const PolarImage& img = sim.render()->polar();
    const std::string path = data_path("golden_default.npy");
    const char* update = std::getenv("SONARSIM_UPDATE_GOLDEN");
    if (update && std::string(update) == "1") {
        write_file_bytes(path, encode_npy(img));
        FAIL("SONARSIM_UPDATE_GOLDEN=1: rewrote the baseline "
             << path << "; unset it and run again (and commit the file)");
    }
    const std::vector<std::uint8_t> bytes = read_file_bytes(path);
    if (bytes.empty())
        FAIL("golden baseline "
             << path << " is missing; create it with SONARSIM_UPDATE_GOLDEN=1 test_accuracy \"[golden]\"");
    const PolarImage gold = decode_npy(bytes);
    REQUIRE(gold.bins == img.bins);
    REQUIRE(gold.beams == img.beams);

    const size_t n = img.level_db.size();
    size_t mask_diff = 0, over_1db = 0;
    std::vector<double> diffs;
    Image8 diff;
    diff.width = img.beams, diff.height = img.bins, diff.channels = 1;
    diff.pixels.assign(n, 0);
    for (int b = 0; b < img.bins; ++b)
        for (int i = 0; i < img.beams; ++i) {
            const float a = img.at(b, i), g = gold.at(b, i);
            std::uint8_t& px =
                diff.pixels[size_t(img.bins - 1 - b) * img.beams + i]; // near range at the bottom
            if (std::isfinite(a) != std::isfinite(g)) {
                ++mask_diff, px = 255;
            } else if (std::isfinite(a)) {
                const double d = std::abs(double(a) - double(g));
                diffs.push_back(d);
                over_1db += d > 1.0;
                px = std::uint8_t(std::lround(255 * std::min(1.0, d)));
            }
        }
    REQUIRE(!diffs.empty());
    std::nth_element(diffs.begin(), diffs.begin() + long(diffs.size() / 2), diffs.end());
    const double median = diffs[diffs.size() / 2], max = *std::max_element(diffs.begin(), diffs.end());
    std::printf(
        "golden: %zu echoing bins, %zu mask differences, median |diff| %.4f dB, max %.4f dB, %zu > 1 dB\n",
        diffs.size(), mask_diff, median, max, over_1db);
    const bool ok = mask_diff <= n / 1000 && median <= 0.05 && over_1db <= n / 1000;
    if (!ok) {
        write_file_bytes(out_path("golden_actual.npy"), encode_npy(img));
        write_file_bytes(out_path("golden_actual.png"), encode_png(polar_gray_image(img, s.display)));
        write_file_bytes(out_path("golden_diff.png"), encode_png(diff));
        FAIL_CHECK("the default scene's image differs from " << path << "; see " << out_path("golden_*")
                                                             << ". If the change is intended, regenerate "
                                                                "with SONARSIM_UPDATE_GOLDEN=1");
    }
    CHECK(mask_diff <= n / 1000);
    CHECK(median <= 0.05);
    CHECK(over_1db <= n / 1000);
}

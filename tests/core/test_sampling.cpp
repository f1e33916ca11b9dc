// The adaptive sampler on a smooth tessellated surface, its ray budget, cancellation and preview.
#include "support.hpp"
#include "core/scene/sampling_scheme.hpp"

#include "core/analysis/reference.hpp"
#include "core/scene/scene_io.hpp"
#include "core/pipeline/simulator.hpp"
#include "core/sampling/adaptive_sampler.hpp"
#include "core/sampling/trace.hpp"
#include "core/grid/sensor_patterns.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <tbb/global_control.h>
#include <sstream>
#include <tuple>

using namespace sonarsim;
using sonarsim::test::out_path;

namespace {

/// A smooth heightfield (a few metres of gentle relief over 16 x 16 m) as an OFF file with n x n vertices.
std::string smooth_terrain_off(int n) {
    const std::string path = out_path("terrain_" + std::to_string(n) + ".off");
    std::ostringstream f;
    f << "OFF\n" << n * n << " " << 2 * (n - 1) * (n - 1) << " 0\n";
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const double x = -8 + 16.0 * i / (n - 1), y = -8 + 16.0 * j / (n - 1);
            f << x << " " << y << " " << 0.6 * std::sin(0.4 * x + 0.3) * std::cos(0.3 * y) << "\n";
        }
    for (int j = 0; j + 1 < n; ++j)
        for (int i = 0; i + 1 < n; ++i) {
            const int a = j * n + i, b = a + 1, c = a + n, d = c + 1;
            f << "3 " << a << " " << b << " " << d << "\n3 " << a << " " << d << " " << c << "\n";
        }
    sonarsim::test::write_text_atomically(path, f.str());
    return path;
}

/// A rough heightfield: the smooth relief plus ripples of 0.7 and 0.45 m wavelength (n x n vertices).
std::string rough_terrain_off(int n) {
    const std::string path = out_path("rough_terrain_" + std::to_string(n) + ".off");
    std::ostringstream f;
    f << "OFF\n" << n * n << " " << 2 * (n - 1) * (n - 1) << " 0\n";
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const double x = -8 + 16.0 * i / (n - 1), y = -8 + 16.0 * j / (n - 1);
            f << x << " " << y << " "
              << 0.6 * std::sin(0.4 * x + 0.3) * std::cos(0.3 * y) + 0.08 * std::sin(9 * x + 2 * y) +
                     0.05 * std::cos(14 * y - 3 * x)
              << "\n";
        }
    for (int j = 0; j + 1 < n; ++j)
        for (int i = 0; i + 1 < n; ++i) {
            const int a = j * n + i, b = a + 1, c = a + n, d = c + 1;
            f << "3 " << a << " " << b << " " << d << "\n3 " << a << " " << d << " " << c << "\n";
        }
    sonarsim::test::write_text_atomically(path, f.str());
    return path;
}

SceneDesc terrain_scene(int n) {
    SceneDesc s;
    s.seafloor.reset();
    s.sonar.pose.position_m = {-2, 0, 2.5};
    s.sonar.pose.orientation_deg = {0, 40, 0};
    ObjectDesc o;
    o.mesh = o.mesh_resolved = smooth_terrain_off(n);
    s.objects.push_back(o);
    return s;
}

} // namespace

TEST_CASE("adaptive rays do not grow with the tessellation of a smooth surface", "[sampling]") {
    // The same surface at 1.4 k and 180 k triangles: a sampler that refines at facet edges needs many
    // times more rays for the finer mesh; one that follows the error needs about the same.
    std::uint64_t rays[2] = {0, 0};
    const int sizes[2] = {28, 301};
    for (int k = 0; k < 2; ++k) {
        const SceneDesc s = terrain_scene(sizes[k]);
        const SceneGeometry g(s);
        const TraceResult t = trace(g, s);
        rays[k] = t.rays_traced;
        // Against a dense spread reference: the error target of the default settings.
        SceneDesc dense = s;
        set_scheme(dense.sampling, SamplingScheme::Spread);
        dense.sampling.elevation_rays = 3000, dense.sampling.azimuth_rays = 4;
        const ImageError e = compare_images(shade(t, s), shade(trace(g, dense), dense));
        INFO("triangles " << 2 * (sizes[k] - 1) * (sizes[k] - 1) << ", rays " << rays[k]);
        CHECK(e.rel_l1 < 0.01);
        CHECK(e.median_abs_db < 0.1);
        CHECK(t.error_estimate.valid);
        CHECK(t.error_estimate.median_abs_db <= s.sampling.tolerance_db);
    }
    CHECK(double(rays[1]) < 1.5 * double(rays[0]));
    const double base = 128.0 * 101;
    CHECK(double(rays[1]) < 2 * base);
}

TEST_CASE("the ray budget holds for refined rays and is reported", "[sampling]") {
    SceneDesc s = default_scene(); // Fig. 9: it refines some thousand rays beyond its 12.9 k base grid
    const SceneGeometry g(s);
    const TraceResult full = trace(g, s);
    const std::uint64_t base = 128 * 101;
    REQUIRE(full.rays_traced > base + 2000);
    CHECK_FALSE(full.error_estimate.budget_reached);
    s.sampling.max_rays = int((base + full.rays_traced) / 2); // half of what the refinement asks
    const TraceResult t = trace(g, s);
    CHECK(t.rays_traced <= std::uint64_t(s.sampling.max_rays));
    CHECK(t.rays_traced >= 128 * 101);
    CHECK(t.error_estimate.budget_reached);
    CHECK(t.error_estimate.valid);
    Simulator sim(s); // the same scene through the pipeline: the budget is reported in the metadata
    const json meta = frame_metadata(s, *sim.render());
    CHECK(meta["sampling_error_estimate"]["budget_reached"] == true);
}

TEST_CASE("at the ray budget the same scene gives the same bytes, however many threads trace it",
          "[sampling]") {
    // The wreck (refinement in elevation and azimuth, the azimuth probe) with a budget that stops each of
    // them part way: which rays the budget pays for is decided in a fixed order, not by thread arrival. On a
    // base grid of 3 rays the wreck and Fig. 9 refine far more than their passes' base grids: there a pass
    // is refused first come and traced again, ordered, from where it started (the wreck's at 95 % with
    // base grids carried to it from the pass before), as is the tank's with multipath on 9. Either way the
    // image is the one a trace that pays every pass in order makes.
    SceneDesc wreck = load_scene(SONARSIM_ASSETS "/scenes/shipwreck.json");
    wreck.sonar.beams = 96, wreck.sonar.range_bins = 400;
    SceneDesc wreck3 = wreck, fig9 = default_scene(), tank = load_scene(SONARSIM_ASSETS "/scenes/tank.json");
    wreck3.sampling.elevation_rays = fig9.sampling.elevation_rays = 3;
    tank.sampling.elevation_rays = 9; // multipath: every group goes on together
    const std::vector<std::pair<SceneDesc, std::vector<double>>> cases = {
        {wreck, {0.5, 0.8, 0.95}}, {wreck3, {0.5, 0.95}}, {fig9, {0.8}}, {tank, {0.8}}};
    for (auto [s, shares] : cases) {
        const SceneGeometry g(s);
        const TraceResult full = trace(g, s);
        REQUIRE_FALSE(full.error_estimate.budget_reached);
        for (const double share : shares) {
            s.sampling.max_rays = int(share * double(full.rays_traced));
            std::vector<std::vector<float>> images;
            std::vector<std::uint64_t> rays;
            for (const int threads : {1, 2, 2, 4}) {
                tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
                const TraceResult t = trace(g, s);
                CHECK(t.error_estimate.budget_reached);
                CHECK(t.rays_traced <= std::uint64_t(s.sampling.max_rays));
                images.push_back(shade(t, s).level_db);
                rays.push_back(t.rays_traced);
            }
            TraceControl ordered;
            ordered.ordered_budget = true;
            const TraceResult t = trace(g, s, ordered);
            images.push_back(shade(t, s).level_db);
            rays.push_back(t.rays_traced);
            const TraceResult again = trace(g, s); // and the estimate the metadata carries
            CHECK(again.error_estimate.passes == t.error_estimate.passes);
            CHECK(again.error_estimate.rel_l1 == t.error_estimate.rel_l1);
            CHECK(again.error_estimate.median_abs_db == t.error_estimate.median_abs_db);
            INFO("elevation rays " << s.sampling.elevation_rays << ", budget " << share << " of "
                                   << full.rays_traced << " rays");
            for (size_t k = 1; k < images.size(); ++k) {
                CHECK(rays[k] == rays[0]);
                CHECK(std::memcmp(images[k].data(), images[0].data(), images[0].size() * 4) == 0);
            }
        }
    }
}

TEST_CASE("a cancelled trace stops and throws, a preview traces the base grid only", "[sampling]") {
    const SceneDesc s = default_scene();
    const SceneGeometry g(s);
    std::atomic<bool> cancel{true};
    TraceControl c;
    c.cancel = &cancel;
    CHECK_THROWS_AS(trace(g, s, c), TraceCancelled);
    SceneDesc spread = s;
    set_scheme(spread.sampling, SamplingScheme::Spread);
    CHECK_THROWS_AS(trace(g, spread, c), TraceCancelled);

    TraceControl preview;
    preview.preview = true;
    const TraceResult p = trace(g, s, preview);
    CHECK(p.preview);
    CHECK(p.rays_traced == std::uint64_t(128) * 101);
    CHECK_FALSE(p.error_estimate.valid);
    // The preview is the spread scheme on the same grid.
    CHECK(compare_images(shade(p, s), shade(trace(g, spread), spread)).rel_l1 < 1e-6);
}

TEST_CASE("the sampler stops on both the median and the rel L1 estimate", "[sampling]") {
    // The smooth terrain: with the rel L1 target out of the way, one pass meets the median target; with a
    // rel L1 target below what that pass estimates, the sampler must go on (a denser base grid) until its
    // estimate meets both, and the measured error falls with it. sampling.estimate fast stops on what it
    // refines: the estimate without its azimuth probe's share, which it reports besides (azimuth_rel_l1).
    SceneDesc s = terrain_scene(301);
    const SceneGeometry g(s);
    SceneDesc dense = s;
    set_scheme(dense.sampling, SamplingScheme::Spread);
    dense.sampling.elevation_rays = 3000, dense.sampling.azimuth_rays = 4;
    const PolarImage ref = shade(trace(g, dense), dense);
    auto refined = [](const TraceResult& t) {
        return t.error_estimate.rel_l1 - t.error_estimate.azimuth_rel_l1;
    };

    s.sampling.tolerance_rel_l1 = 1; // median only
    const TraceResult one = trace(g, s);
    REQUIRE(one.error_estimate.valid);
    CHECK(one.error_estimate.passes == 1);
    CHECK(one.error_estimate.median_abs_db <= s.sampling.tolerance_db);
    CHECK(one.error_estimate.azimuth_rel_l1 > 0);
    const ImageError e1 = compare_images(shade(one, s), ref);

    SceneDesc tight = s;
    tight.sampling.tolerance_rel_l1 = 0.5 * refined(one); // median met, rel L1 not
    const TraceResult both = trace(g, tight);
    const ImageError e2 = compare_images(shade(both, tight), ref);
    INFO("one pass: " << one.rays_traced << " rays, estimate " << one.error_estimate.rel_l1 << " (azimuth "
                      << one.error_estimate.azimuth_rel_l1 << "), measured " << e1.rel_l1
                      << "; both targets: " << both.rays_traced << " rays, estimate "
                      << both.error_estimate.rel_l1 << " (azimuth " << both.error_estimate.azimuth_rel_l1
                      << "), measured " << e2.rel_l1);
    CHECK(both.error_estimate.passes > 1);
    CHECK_FALSE(both.error_estimate.budget_reached);
    CHECK(refined(both) <= tight.sampling.tolerance_rel_l1);
    CHECK(both.rays_traced > one.rays_traced);
    CHECK(e2.rel_l1 < e1.rel_l1);
    // The estimate stays honest: above the measured error. Its elevation part is below 2x the whole
    // measured error here (second order on this smooth terrain, counted so on smooth triples); its azimuth
    // part is not sharp on a smooth terrain: the probe's cells, every ninth, are scaled by nine, and what
    // neighbouring cells' differences cancel in a bin the sparse cells do not. With the echo spread along
    // each cell's trend the image's error fell 3x and the probe's share did not (measured: 0.142 % for
    // 0.022 %, and 0.146 % for 0.012 % once the elevation part is refined to 0.004 %; before the trend,
    // 0.245 % for 0.063 %).
    CHECK(one.error_estimate.rel_l1 >= e1.rel_l1);
    CHECK(one.error_estimate.rel_l1 <= 10 * e1.rel_l1);
    CHECK(both.error_estimate.rel_l1 >= e2.rel_l1);
    CHECK(refined(both) <= 2 * e2.rel_l1);
    CHECK(both.error_estimate.rel_l1 <= 15 * e2.rel_l1);
    Simulator sim(tight);
    const json meta = frame_metadata(tight, *sim.render());
    const json& est = meta["sampling_error_estimate"];
    CHECK(est["rel_l1"].get<double>() == Approx(both.error_estimate.rel_l1));
    CHECK(est["azimuth_rel_l1"].get<double>() == Approx(both.error_estimate.azimuth_rel_l1));
    // What it reports is what tolerance_met judges: here the probe's share keeps it above the target.
    CHECK(est["tolerance_met"] == both.error_estimate.meets(tight.sampling));
    CHECK(est["tolerance_met"] == false);
    // The report says how far its probe looks beside the number.
    CHECK(est["not_seen"].get<std::string>().find("ninth") != std::string::npos);
}

TEST_CASE("no holes on a grazing rough floor against a dense reference", "[sampling]") {
    // A rough terrain seen at grazing incidence (5 deg down, 1.2 m up): crests, shadows behind them and
    // long footprints, and ripples across each beam. Bins the dense reference sees echo in must echo in
    // the image too. Most of what one ray column per beam leaves here is across the beam's width: strict
    // refines it; fast reports it (azimuth_rel_l1) and says the tolerance is not met.
    SceneDesc s;
    s.seafloor.reset();
    s.sonar.pose.position_m = {-7.5, 0, 1.2};
    s.sonar.pose.orientation_deg = {0, 5, 0};
    s.sonar.range_max_m = 8;
    ObjectDesc o;
    o.mesh = o.mesh_resolved = rough_terrain_off(401);
    s.objects.push_back(o);
    const SceneGeometry g(s);
    SceneDesc dense = s;
    set_scheme(dense.sampling, SamplingScheme::Spread);
    dense.sampling.elevation_rays = 6561, dense.sampling.azimuth_rays = 3;
    const PolarImage ref = shade(trace(g, dense), dense);
    // Holes that matter: bins within 40 dB of the image's peak. Below that the reference's own spreading
    // leaves echo where no surface is (a cell at grazing incidence on a facet nearly along its edge rays
    // spreads its echo centimetres to decimetres past the crest it lies on), which a finer sampler does
    // not reproduce: those bins count as holes but carry no measurable part of the image.
    float peak = -INFINITY;
    for (float v : ref.level_db) peak = std::max(peak, v);
    for (const ErrorEstimate how : {ErrorEstimate::Strict, ErrorEstimate::Fast}) {
        s.sampling.estimate = how;
        const TraceResult t = trace(g, s);
        const PolarImage img = shade(t, s);
        const ImageError e = compare_images(img, ref);
        long holes_40db = 0;
        for (size_t n = 0; n < ref.level_db.size(); ++n)
            if (ref.level_db[n] > peak - 40 && !(img.level_db[n] > -INFINITY)) ++holes_40db;
        const auto& est = t.error_estimate;
        INFO((how == ErrorEstimate::Strict ? "strict" : "fast")
             << ": rays " << t.rays_traced << ", rel L1 " << e.rel_l1 << ", median " << e.median_abs_db
             << " dB, holes " << e.holes << " of " << e.echoing_ref << ", within 40 dB of the peak "
             << holes_40db << "; passes " << est.passes << ", estimate " << est.rel_l1 << " (azimuth "
             << est.azimuth_rel_l1 << ")");
        REQUIRE(e.echoing_ref > 8000);
        CHECK(e.median_abs_db < 0.1);
        CHECK(est.rel_l1 >= e.rel_l1); // honest either way
        CHECK(est.rel_l1 <= 3 * e.rel_l1);
        // Measured: strict 0.35 % (three ray columns per beam; holes 0.99 % of the bins), fast 1.5 %, holes
        // 0.58 % (0.33 % before its estimate took smooth triples at second order), estimated 3.2 %, 3.0 % of
        // it across the beams. Either falls short of holes within 0.5 % (docs/accuracy-and-speed.md).
        CHECK(double(holes_40db) <= 0.012 * double(e.echoing_ref));
        if (how == ErrorEstimate::Strict) {
            CHECK(e.rel_l1 < 0.005);
            CHECK(est.meets(s.sampling));
        } else {
            CHECK(e.rel_l1 < 0.02);
            CHECK(est.azimuth_rel_l1 > 0.5 * est.rel_l1);
            CHECK_FALSE(est.meets(s.sampling));
        }
    }
}

TEST_CASE("both estimates track the measured error and strict refines what fast reports", "[sampling]") {
    // sampling.estimate strict against fast, each against a dense reference. Both count smooth triples at
    // second order and probe the error across a beam's width (three ray columns against one); fast reports
    // the probe's share, strict adds ray columns where it is the larger one. On the smooth terrain neither
    // adds columns; on the rough terrain at grazing incidence, one ray column per beam misses ripples
    // across the beam: strict refines them.
    auto measure = [](SceneDesc s, ErrorEstimate how) {
        const SceneGeometry g(s);
        SceneDesc dense = s;
        set_scheme(dense.sampling, SamplingScheme::Spread);
        dense.sampling.elevation_rays = 3000, dense.sampling.azimuth_rays = 9;
        const PolarImage ref = shade(trace(g, dense), dense);
        s.sampling.estimate = how;
        const TraceResult t = trace(g, s);
        const ImageError e = compare_images(shade(t, s), ref);
        CHECK(e.echoing_ref > 1000);
        return std::make_tuple(t.error_estimate.rel_l1, e.rel_l1, t.error_estimate.median_abs_db,
                               e.median_abs_db, t.error_estimate.azimuth_rel_l1);
    };
    SceneDesc smooth = terrain_scene(301);
    SceneDesc rough = smooth;
    rough.objects[0].mesh = rough.objects[0].mesh_resolved = rough_terrain_off(401);
    rough.sonar.pose.position_m = {-7.5, 0, 1.2};
    rough.sonar.pose.orientation_deg = {0, 5, 0};
    rough.sonar.range_max_m = 8;
    for (const bool is_rough : {false, true}) {
        const SceneDesc& s = is_rough ? rough : smooth;
        // Measured (the echo spread along each cell's trend): smooth, fast 0.142 % (0.131 % of it azimuth)
        // and strict 0.149 % against 0.022 % (before the trend: 0.245 and 0.251 % against 0.063 %: the
        // image's error fell, the azimuth probe's overstatement on a smooth surface did not); rough, fast
        // 2.8 % (2.5 % azimuth) against 1.42 % and strict 0.53 % against 0.37 % (before: 3.2 % against 1.46 %
        // and 0.52 % against 0.38 %).
        const auto [fast_est, fast_err, fast_med_est, fast_med, fast_az] = measure(s, ErrorEstimate::Fast);
        const auto [strict_est, strict_err, strict_med_est, strict_med, strict_az] =
            measure(s, ErrorEstimate::Strict);
        INFO((is_rough ? "rough" : "smooth")
             << ": fast estimate " << fast_est << " (azimuth " << fast_az << ") measured " << fast_err
             << "; strict estimate " << strict_est << " measured " << strict_err);
        const double within = is_rough ? 4 : 8;
        CHECK(fast_est >= fast_err);
        CHECK(fast_est <= within * fast_err);
        CHECK(fast_med_est >= fast_med);
        CHECK(strict_est >= strict_err);
        CHECK(strict_est <= within * strict_err);
        CHECK(strict_med_est >= strict_med);
        CHECK(fast_az > 0);
        CHECK(strict_az == 0); // strict acts on it: nothing is left unrefined for it to report
        if (is_rough) {
            CHECK(fast_az > 0.5 * fast_est);
            CHECK(strict_err < 0.3 * fast_err);
        } else {
            CHECK(strict_err == Approx(fast_err).epsilon(0.05)); // no columns added
        }
    }
}

TEST_CASE("the estimate stays at or above the measured error when the tolerances are loosened",
          "[sampling]") {
    // The Monterey canyon wall (real bathymetry) at tolerances a user picks for speed. Measured: 1.07 % and
    // 1.02 % for 0.43 % (2.5x, 2.4x). It said 0.97x and 0.91x when the estimate's smooth test took the loose
    // tolerance's own level steps (3 and 10 dB; RefineCriteria::edge_between now keeps the default's, its
    // own test in test_refine_criteria.cpp) and cells spread their echo evenly (then 1.0 % measured); with
    // each cell's trend the error is 0.43 % either way.
    SceneDesc s = load_scene(SONARSIM_ASSETS "/scenes/monterey.json");
    const SceneGeometry g(s);
    SceneDesc dense = s;
    set_scheme(dense.sampling, SamplingScheme::Spread);
    dense.sampling.elevation_rays = 729, dense.sampling.azimuth_rays = 3; // 0.05 % from 2187 x 9 here
    const PolarImage ref = shade(trace(g, dense), dense);
    for (const auto& [rel, db] : {std::pair(0.01, 0.3), std::pair(0.1, 1.0)}) {
        s.sampling.tolerance_rel_l1 = rel, s.sampling.tolerance_db = db;
        const TraceResult t = trace(g, s);
        const ImageError e = compare_images(shade(t, s), ref);
        INFO("tolerances " << rel << ", " << db << " dB: estimate " << t.error_estimate.rel_l1 << " measured "
                           << e.rel_l1);
        REQUIRE(e.echoing_ref > 10000);
        CHECK(e.rel_l1 > 0.003); // loose enough to matter
        CHECK(t.error_estimate.rel_l1 >= 1.05 * e.rel_l1);
        CHECK(t.error_estimate.rel_l1 <= 3 * e.rel_l1);
    }
}

TEST_CASE("an image of 512 beams, estimated on every 8th beam, says at least its measured error",
          "[sampling]") {
    // Monterey's canyon (real bathymetry) seen by 512 beams over the same 90 degrees, fewer bins to keep it
    // quick. From 512 beams the estimate's sample beams are every 8th (kWideEstimateStride), groups of eight.
    SceneDesc s = load_scene(SONARSIM_ASSETS "/scenes/monterey.json");
    s.sonar.beams = 512, s.sonar.range_bins = 300;
    const SceneGeometry g(s);
    SceneDesc dense = s;
    set_scheme(dense.sampling, SamplingScheme::Spread);
    dense.sampling.elevation_rays = 729, dense.sampling.azimuth_rays = 3;
    const PolarImage ref = shade(trace(g, dense), dense);
    const TraceResult t = trace(g, s);
    const ImageError e = compare_images(shade(t, s), ref);
    INFO("estimate " << t.error_estimate.rel_l1 << " measured " << e.rel_l1 << " rays " << t.rays_traced);
    REQUIRE(e.echoing_ref > 20000);
    CHECK(e.rel_l1 > 0.001); // enough error for the comparison to mean something
    CHECK(e.rel_l1 < s.sampling.tolerance_rel_l1);
    CHECK(t.error_estimate.rel_l1 >= e.rel_l1);
    // Overstated 3.5x here with every 4th beam as with every 8th (0.645 and 0.624 % for 0.18 %): the azimuth
    // probe's lone cells on smooth bathymetry (bench/NOTEBOOK.md, "Why fast's probe overstates").
    CHECK(t.error_estimate.rel_l1 <= 4 * e.rel_l1);
}

TEST_CASE("a smooth elevation pattern's base grid is dense where the pattern is strong, in equal shares",
          "[sampling]") {
    using adaptive::kPatternExponent;
    using adaptive::kTailDensity;
    SceneDesc s = default_scene();
    s.sensor.elevation_beamwidth_deg = 12;
    for (auto kind : {ElevationPattern::Gaussian, ElevationPattern::Sinc})
        for (int M : {101, 99, 31}) { // an incomplete last triple of 2 cells, none, and 1
            s.sensor.elevation_pattern = kind;
            const ElevationWeight w(s);
            const double phi = w.traced_fov_rad();
            const std::vector<double> e = adaptive::pattern_grid(w, phi, M);
            REQUIRE(e.size() == size_t(M) + 1);
            CHECK(e.front() == phi / 2);
            CHECK(e.back() == -phi / 2);
            for (int j = 0; j < M; ++j) CHECK(e[size_t(j)] > e[size_t(j) + 1]);
            // Each whole triple: three equal cells holding an equal share of the density's integral,
            // integrated here independently (midpoint rule, 20000 steps per triple).
            auto share = [&](double top, double bottom) {
                const int n = 20000;
                double sum = 0;
                for (int k = 0; k < n; ++k) {
                    const double x = top - (k + 0.5) * (top - bottom) / n;
                    sum += std::max(kTailDensity, std::pow(w(x), kPatternExponent));
                }
                return sum * (top - bottom) / n;
            };
            const int T = M / 3;
            const double unit = share(phi / 2, -phi / 2) / (T + (M % 3) / 3.0);
            for (int t = 0; t < T; ++t) {
                const double a = e[size_t(3 * t)], b = e[size_t(3 * t + 1)], c = e[size_t(3 * t + 2)],
                             d = e[size_t(3 * t + 3)];
                CHECK(a - b == Approx(b - c).epsilon(1e-9));
                CHECK(b - c == Approx(c - d).epsilon(1e-9));
                CHECK(share(a, d) == Approx(unit).epsilon(2e-4));
            }
            for (int j = 3 * T; j < M; ++j)
                CHECK(share(e[size_t(j)], e[size_t(j) + 1]) == Approx(unit / 3).epsilon(2e-4));
            // The main lobe's cells against the tails': the density's ratio there, 1 to kTailDensity.
            const int mid = (M / 2 / 3) * 3;
            const double centre = e[size_t(mid)] - e[size_t(mid) + 1], outer = e[0] - e[1];
            CHECK(centre / outer == Approx(kTailDensity).epsilon(0.06));
        }
    s.sensor.elevation_pattern = ElevationPattern::Flat;
    const ElevationWeight flat(s);
    const std::vector<double> e = adaptive::pattern_grid(flat, 0.3, 101);
    for (int j = 0; j <= 101; ++j) CHECK(e[size_t(j)] == Approx(0.15 - j * 0.3 / 101).margin(1e-15));
}

TEST_CASE("the adaptive tracer runs the whole image's pass through its caller's and hands back the pass of "
          "its hits",
          "[sampling]") {
    // When its first pass traces every group, the adaptive tracer shades the whole image to place the rays,
    // with the channels the caller asked for, and that is the caller's pass of the hits returned (loose
    // targets). The multipath tank at a tight target refines every group again after that shading: what the
    // caller takes then must be the pass of the hits as returned, never of the earlier ones.
    SceneDesc s = load_scene(SONARSIM_ASSETS "/scenes/tank.json");
    s.sonar.range_bins = 300;
    const SceneGeometry g(s);
    Channels wanted;
    wanted.image = wanted.ground_truth = true;
    for (const double rel_l1 : {1.0, 0.002}) {
        SceneDesc a = s;
        a.sampling.tolerance_rel_l1 = rel_l1, a.sampling.tolerance_db = 0.01;
        ImagePass pass(wanted);
        const TraceResult t = trace(g, a, {}, &pass);
        INFO("tolerance " << rel_l1 << ": " << t.error_estimate.passes << " passes");
        CHECK(t.error_estimate.passes == (rel_l1 == 1.0 ? 1 : 3));
        const auto taken = pass.take();
        if (rel_l1 == 1.0) REQUIRE(taken);
        if (!taken) continue;
        const Accumulation fresh = accumulate(t, a, wanted);
        CHECK(taken->image->level_db == fresh.image->level_db);
        REQUIRE(taken->truth);
        const auto& got = taken->truth->elevation_deg; // NaN where nothing echoes: compared as bytes
        REQUIRE(got.size() == fresh.truth->elevation_deg.size());
        CHECK(std::memcmp(got.data(), fresh.truth->elevation_deg.data(), got.size() * sizeof(float)) == 0);
        CHECK_FALSE(pass.take()); // handed over once
    }
}

// The adaptive sampler on a smooth tessellated surface, its ray budget, cancellation and preview.
#include "support.hpp"
#include "core/scene/sampling_scheme.hpp"

#include "core/analysis/reference.hpp"
#include "core/scene/scene_io.hpp"
#include "core/pipeline/simulator.hpp"
#include "core/sampling/trace.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>

using namespace sonarsim;
using sonarsim::test::out_path;

namespace {

/// A smooth heightfield (a few metres of gentle relief over 16 x 16 m) as an OFF file with n x n vertices.
std::string smooth_terrain_off(int n) {
    const std::string path = out_path("terrain_" + std::to_string(n) + ".off");
    std::ofstream f(path);
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
        const ImageError e = compare_images(*t.shaded->image, shade(trace(g, dense), dense));
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
    REQUIRE(p.shaded);
    // The preview is the spread scheme on the same grid.
    CHECK(compare_images(*p.shaded->image, shade(trace(g, spread), spread)).rel_l1 < 1e-6);
}

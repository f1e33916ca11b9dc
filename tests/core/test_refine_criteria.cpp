// The adaptive sampler's refinement criteria on hand-made cells: which neighbour pairs (and single cells)
// it splits. Each node is built from a plane it hits, as the tracer would build it (trace_node), so the
// test asserts the decision alone, without tracing a scene.
#include "core/sampling/refine_criteria.hpp"

#include "core/data/pose.hpp"
#include "core/base/recent_values.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <thread>

using namespace sonarsim;
using namespace sonarsim::adaptive;

namespace {

/// A sonar at the origin looking along +x (z up); range window [0.5, 10) m in 512 bins (1.86 cm); two
/// objects (materials 1 and 2) and the seafloor, for material_of().
SceneDesc criteria_scene() {
    SceneDesc s;
    s.sonar.pose.position_m = {0, 0, 0};
    s.sonar.pose.orientation_deg = {0, 0, 0};
    s.sonar.range_min_m = 0.5, s.sonar.range_max_m = 10, s.sonar.range_bins = 512;
    s.sampling.tolerance_db = 0.1;
    ObjectDesc box;
    box.box_m = Vec3d{1, 1, 1};
    s.objects = {box, box};
    return s;
}

/// The cell of width de (elevation) around the ray (a, e) that meets the plane through `on` with normal
/// `normal`, on material `material`, triangle `prim`, with echo density `density_db`.
Node plane_node(const detail::RayFrame& f, const RefineCriteria& c, double a_rad, double e_rad, double de,
                const glm::dvec3& on, const glm::dvec3& normal, unsigned material, unsigned prim,
                double density_db) {
    const Angle a(a_rad);
    Node n;
    n.de = de, n.angle = Angle(e_rad);
    const glm::dvec3 d = f.dir(a, n.angle);
    const glm::dvec3 nn = glm::normalize(normal);
    const double t = detail::plane_range(f.origin, on, nn, d);
    REQUIRE(t > 0);
    n.hit = Hit{t, nn, material, prim, nn};
    n.p_m = f.origin + t * d;
    n.density_db = density_db;
    const glm::dvec3 d_e = f.R * glm::dvec3(-n.angle.s * a.c, -n.angle.s * a.s, n.angle.c);
    n.dr_de = std::abs(t * glm::dot(nn, d_e) / glm::dot(nn, d));
    set_width(n, de, c.bin_m());
    return n;
}

/// A cell whose ray meets nothing.
Node miss_node(double e_rad, double de) {
    Node n;
    n.de = de, n.angle = Angle(e_rad);
    return n;
}

Column column(double da) {
    Column c;
    c.a = 0, c.da = da, c.beam = 0;
    return c;
}

/// Whether the elevation neighbours x (above) and y in column c must split, as refine_column asks (the edge
/// ray by the angle-sum identities from x), checked against the edge ray from its own sine and cosine.
bool split_pair(const RefineCriteria& crit, const Node& x, const Node& y, const Column& c) {
    const Angle a(c.a);
    const bool exact = crit.discontinuous(x, c, y, c, EdgeRay{a, x.angle.rad - x.de / 2});
    const bool near =
        crit.discontinuous(x, c, y, c, EdgeRay{a, x.angle.rad - x.de / 2, nullptr, &x.angle, x.de});
    REQUIRE(near == exact);
    return near;
}

const double kDe = deg2rad(1.0); // 1 deg cells

} // namespace

TEST_CASE("criteria: a silhouette pair on one object is flagged, a smooth facet edge is not",
          "[sampling][criteria]") {
    const SceneDesc s = criteria_scene();
    const detail::RayFrame f(s);
    const RefineCriteria crit(s, f, false);
    const Column c = column(kDe);
    const double e_x = kDe / 2, e_y = -kDe / 2;

    SECTION("silhouette: the upper cell sees a near face, the lower one a face of the same object behind") {
        const Node x = plane_node(f, crit, 0, e_x, kDe, {3, 0, 0}, {-1, 0, 0}, 1, 4, 40);
        const Node y = plane_node(f, crit, 0, e_y, kDe, {5, 0, 0}, {-1, 0.2, 0}, 1, 9, 40);
        CHECK(split_pair(crit, x, y, c));
    }
    SECTION("smooth: adjacent facets of a finely tessellated sphere, tangent planes at the hits") {
        // Sphere of radius 3 m centred 6 m ahead: the hits are 5 cm apart, their normals 1 deg apart; the
        // tangent planes meet the edge ray within microns of each other.
        const glm::dvec3 centre{6, 0, 0};
        auto on_sphere = [&](double e) {
            const glm::dvec3 d = f.dir(Angle(0), Angle(e));
            const double b = glm::dot(d, centre), t = b - std::sqrt(b * b - glm::dot(centre, centre) + 9.0);
            return t * d;
        };
        const glm::dvec3 px = on_sphere(e_x), py = on_sphere(e_y);
        const Node x = plane_node(f, crit, 0, e_x, kDe, px, px - centre, 1, 100, 40.0);
        const Node y = plane_node(f, crit, 0, e_y, kDe, py, py - centre, 1, 101, 40.02);
        REQUIRE(glm::dot(x.hit->normal, y.hit->normal) < std::cos(0.1 * kDe)); // the planes do differ
        CHECK_FALSE(split_pair(crit, x, y, c));
        // The same pair with a 30 deg crease between the facets moves the edge's range by 1.5 cm (most of a
        // bin): a surface edge.
        const glm::dvec3 creased = glm::dvec3(-std::cos(0.52), 0, -std::sin(0.52));
        const Node z = plane_node(f, crit, 0, e_y, kDe, py, creased, 1, 101, 40.02);
        CHECK(split_pair(crit, x, z, c));
    }
}

TEST_CASE("criteria: a grazing pair on one plane is flagged, a steep one is not", "[sampling][criteria]") {
    const SceneDesc s = criteria_scene();
    const detail::RayFrame f(s);
    const RefineCriteria crit(s, f, false);
    const double de = deg2rad(1.0);
    const Column c = column(de);
    const glm::dvec3 floor_point{0, 0, -0.5}, up{0, 0, 1};
    auto floor_node = [&](double e_deg) {
        return plane_node(f, crit, 0, deg2rad(e_deg), de, floor_point, up, kFloorMaterial, 0,
                          40); // one level: only the range spreading differs
    };
    SECTION("grazing: footprints of metres, whose echo per metre of range differs by dB") {
        const Node x = floor_node(-3.5), y = floor_node(-4.5);
        REQUIRE(x.footprint_m > crit.bin_m());
        REQUIRE(std::abs(x.per_metre_db - y.per_metre_db) > 4 * s.sampling.tolerance_db);
        CHECK(split_pair(crit, x, y, c));
    }
    SECTION("steep: footprints within a bin") {
        const Node x = floor_node(-60), y = floor_node(-61);
        REQUIRE(y.footprint_m < crit.bin_m());
        CHECK_FALSE(split_pair(crit, x, y, c));
    }
}

TEST_CASE("criteria: a miss next to a hit is flagged, two misses are not", "[sampling][criteria]") {
    const SceneDesc s = criteria_scene();
    const detail::RayFrame f(s);
    const RefineCriteria crit(s, f, false);
    const Column c = column(kDe);
    const Node hit = plane_node(f, crit, 0, kDe / 2, kDe, {3, 0, 0}, {-1, 0, 0}, 1, 0, 40);
    const Node miss = miss_node(-kDe / 2, kDe), miss_above = miss_node(kDe / 2, kDe);
    CHECK(split_pair(crit, hit, miss, c));
    CHECK(split_pair(crit, miss_above, plane_node(f, crit, 0, -kDe / 2, kDe, {3, 0, 0}, {-1, 0, 0}, 1, 0, 40),
                     c));
    CHECK_FALSE(split_pair(crit, miss_above, miss, c));
}

TEST_CASE("criteria: different materials are flagged, one material on one plane is not",
          "[sampling][criteria]") {
    const SceneDesc s = criteria_scene();
    const detail::RayFrame f(s);
    const RefineCriteria crit(s, f, false);
    const Column c = column(kDe);
    // One wall 3 m ahead, the same level on both sides: only the material tells them apart.
    const Node x = plane_node(f, crit, 0, kDe / 2, kDe, {3, 0, 0}, {-1, 0, 0.3}, 1, 0, 40);
    const Node y1 = plane_node(f, crit, 0, -kDe / 2, kDe, {3, 0, 0}, {-1, 0, 0.3}, 1, 0, 40);
    const Node y2 = plane_node(f, crit, 0, -kDe / 2, kDe, {3, 0, 0}, {-1, 0, 0.3}, 2, 0, 40);
    CHECK_FALSE(split_pair(crit, x, y1, c));
    CHECK(split_pair(crit, x, y2, c));
    // A step in level on one material is a discontinuity too (10 x tolerance_db: 1 dB).
    const Node y3 = plane_node(f, crit, 0, -kDe / 2, kDe, {3, 0, 0}, {-1, 0, 0.3}, 1, 0, 41.5);
    CHECK(split_pair(crit, x, y3, c));
}

TEST_CASE("criteria: the estimate's smooth test keeps the default tolerance's level steps when the "
          "tolerance is looser",
          "[sampling][criteria]") {
    // A wall 3 m ahead, one material and triangle; steep, so only the step in echo density can tell the
    // cells apart. Refinement (discontinuous) looks for steps of 10 x tolerance_db; the error estimate
    // (edge_between) for steps of at most 10 x kSmoothToleranceDb = 1 dB, however loose the tolerance.
    const Column c = column(kDe);
    auto pair_steps = [&](double tolerance_db, double step_db) {
        SceneDesc s = criteria_scene();
        s.sampling.tolerance_db = tolerance_db;
        const detail::RayFrame f(s);
        const RefineCriteria crit(s, f, false);
        const Node x = plane_node(f, crit, 0, kDe / 2, kDe, {3, 0, 0}, {-1, 0, 0.3}, 1, 0, 40);
        const Node y = plane_node(f, crit, 0, -kDe / 2, kDe, {3, 0, 0}, {-1, 0, 0.3}, 1, 0, 40 + step_db);
        REQUIRE(y.footprint_m < crit.bin_m());
        const Angle a(0);
        const bool edge =
            crit.edge_between(x, y, EdgeRay{a, x.angle.rad - x.de / 2, nullptr, &x.angle, x.de});
        return std::pair(split_pair(crit, x, y, c), edge);
    };
    using P = std::pair<bool, bool>;                // (refinement splits, the estimate sees an edge)
    CHECK(pair_steps(0.3, 2.0) == P{false, true});  // a loose tolerance leaves it; still a kink
    CHECK(pair_steps(0.3, 0.8) == P{false, false}); // below 1 dB: smooth for both
    CHECK(pair_steps(1.0, 5.0) == P{false, true});
    CHECK(pair_steps(0.1, 1.2) == P{true, true}); // the default: the same steps for both
    CHECK(pair_steps(0.1, 0.8) == P{false, false});
    CHECK(pair_steps(0.05, 0.7) == P{true, true}); // tighter: the tolerance's own steps (0.5 dB)
    CHECK(pair_steps(0.05, 0.3) == P{false, false});

    // Grazing on the floor, one level: the echo per metre of range steps (4 x tolerance_db refines, at
    // most 4 x kSmoothToleranceDb = 0.4 dB for the estimate).
    SceneDesc s = criteria_scene();
    s.sampling.tolerance_db = 0.6;
    const detail::RayFrame f(s);
    const RefineCriteria crit(s, f, false);
    auto floor_node = [&](double e_deg) {
        return plane_node(f, crit, 0, deg2rad(e_deg), kDe, {0, 0, -0.5}, {0, 0, 1}, kFloorMaterial, 0, 40);
    };
    const Node x = floor_node(-3.5), y = floor_node(-4.5);
    const double per_metre_step_db = std::abs(x.per_metre_db - y.per_metre_db);
    REQUIRE(per_metre_step_db > 0.4);
    REQUIRE(per_metre_step_db < 2.4);
    CHECK_FALSE(split_pair(crit, x, y, c));
    CHECK(crit.edge_between(x, y, EdgeRay{Angle(0), x.angle.rad - x.de / 2, nullptr, &x.angle, x.de}));
}

TEST_CASE("criteria: an edge is split only where its error is significant against the base image",
          "[sampling][criteria]") {
    const SceneDesc s = criteria_scene();
    const detail::RayFrame f(s);
    RefineCriteria crit(s, f, false);
    const Column c = column(kDe);
    const Node x = plane_node(f, crit, 0, kDe / 2, kDe, {3, 0, 0}, {-1, 0, 0}, 1, 0, 40);
    const Node y = plane_node(f, crit, 0, -kDe / 2, kDe, {3, 0, 0}, {-1, 0, 0}, 2, 0, 40);
    const int bin = int(std::floor((x.hit->t - s.sonar.range_min_m) / crit.bin_m()));
    // Half a cell of 1 deg x 1 deg at 40 dB/sr echoes about 2 dB; the base image's bin decides.
    crit.base_db.assign(size_t(s.sonar.range_bins), -std::numeric_limits<float>::infinity());
    CHECK(split_pair(crit, x, y, c));  // nothing else in the bin: the edge is all of it
    crit.base_db[size_t(bin)] = 40.0f; // 38 dB brighter: the edge's error is negligible there
    CHECK_FALSE(split_pair(crit, x, y, c));
    crit.base_db[size_t(bin)] = -10.0f; // comparable: significant again
    CHECK(split_pair(crit, x, y, c));
}

TEST_CASE("criteria: the significance bound never rules out a cell whose error is significant",
          "[sampling][criteria]") {
    // may_be_significant lets the pair test skip its geometry; it must be false only where significant()
    // is false for every fraction f <= 1/2. Cells on planes at many ranges, widths and grazing angles (so
    // that the footprint spans less or more than a bin), against base image levels around the threshold.
    const SceneDesc s = criteria_scene();
    const detail::RayFrame f(s);
    RefineCriteria crit(s, f, false);
    crit.base_db.assign(size_t(s.sonar.range_bins), -std::numeric_limits<float>::infinity());
    int ruled_out = 0, kept = 0, both = 0;
    for (int k = 0; k < 3000; ++k) {
        const double de = deg2rad(0.01 + 2.0 * (k % 17) / 17), slope = 0.05 + 0.9 * (k % 13) / 13;
        const double e = -deg2rad(1 + 20.0 * (k % 11) / 11);
        const Node n =
            plane_node(f, crit, 0, e, de, {0, 0, -1}, {-slope, 0, 1}, kFloorMaterial, 0, -20 + 0.037 * k);
        const Column c = column(deg2rad(0.05 + (k % 7) * 0.3));
        const int bin = int(std::floor((n.hit->t - s.sonar.range_min_m) / crit.bin_m()));
        if (bin < 0 || bin >= s.sonar.range_bins) continue;
        // Levels from far below to far above what the cell's error amounts to.
        crit.base_db[size_t(bin)] = float(-60 + (k % 23) * 6.0);
        const bool may = crit.may_be_significant(n, c);
        bool any = false;
        for (double frac : {0.5, 0.5 - 1e-12, 0.3, 0.01}) any = any || crit.significant(n, c, frac);
        INFO("k " << k << ": significant " << any << ", bound " << may);
        REQUIRE((!any || may)); // never ruled out when significant
        ruled_out += !may, kept += may && !any, both += may && any;
        crit.base_db[size_t(bin)] = -std::numeric_limits<float>::infinity();
    }
    CHECK(ruled_out > 300); // the bound decides often ...
    CHECK(both > 300);      // ... and is not simply always true
}

TEST_CASE("criteria: a cell with a plane horizon or a specular lobe inside splits on its own",
          "[sampling][criteria]") {
    SceneDesc s = criteria_scene();
    s.objects[0].material.mu = 1, s.objects[0].material.h_deg = 0.5;
    s.sonar.frequency_khz = 1; // no absorption worth splitting for: only the horizon and the lobe
    const detail::RayFrame f(s);
    const RefineCriteria crit(s, f, false);
    const double de = deg2rad(2.0);
    // A floor 0.2 m below seen at -0.5 deg in a 2 deg cell: the cell's upper edge (+0.5 deg) never meets it.
    const Node horizon =
        plane_node(f, crit, 0, deg2rad(-0.5), de, {0, 0, -0.2}, {0, 0, 1}, kFloorMaterial, 0, 40);
    CHECK(crit.needs_split_alone(horizon, Angle(0)));
    const Node below =
        plane_node(f, crit, 0, deg2rad(-20), de, {0, 0, -0.2}, {0, 0, 1}, kFloorMaterial, 0, 40);
    CHECK_FALSE(crit.needs_split_alone(below, Angle(0)));
    // A specular wall (lobe 0.5 deg) seen at normal incidence inside a 2 deg cell; a lobe far outside: no.
    const Node specular = plane_node(f, crit, 0, deg2rad(0.3), de, {3, 0, 0}, {-1, 0, 0}, 1, 0, 40);
    CHECK(crit.needs_split_alone(specular, Angle(0)));
    const Node tilted = plane_node(f, crit, 0, deg2rad(0.3), de, {3, 0, 0}, {-1, 0, 0.5}, 1, 0, 40);
    CHECK_FALSE(crit.needs_split_alone(tilted, Angle(0)));
}

TEST_CASE("criteria: the horizon test agrees with exact edge rays, also where the ray grazes at about de / 2",
          "[sampling][criteria]") {
    SceneDesc s = criteria_scene();
    s.sonar.frequency_khz = 1; // no absorption worth splitting for: only the horizon
    const detail::RayFrame f(s);
    const RefineCriteria crit(s, f, false);
    // A floor 1 m below, seen at elevations e whose grazing angle -e sweeps across de / 2 for each width:
    // the shortcut (n.d keeps its sign at both edges) must never skip a horizon the edges see.
    int horizons = 0, clear = 0;
    for (double de_deg : {0.01, 0.3, 2.0, 20.0, 50.0}) {
        const double de = deg2rad(de_deg);
        for (int k = 0; k <= 400; ++k) {
            const double e = -(de / 2) * (0.9 + 0.2 * k / 400.0) - 1e-9 * (k % 3); // |e| near de / 2
            const Node n = plane_node(f, crit, 0.1, e, de, {0, 0, -1}, {0, 0, 1}, kFloorMaterial, 0, 40);
            // Exact: the upper edge ray (e + de / 2, sin and cos evaluated) meets the plane or not.
            const glm::dvec3 up = f.dir(Angle(0.1), Angle(e + de / 2));
            const bool exact = detail::plane_range(f.origin, n.p_m, n.hit->face_normal, up) < 0;
            if (std::abs(-e - de / 2) < 1e-12) continue; // the edge grazes: either answer is right
            REQUIRE(crit.needs_split_alone(n, Angle(0.1)) == exact);
            (exact ? horizons : clear) += 1;
        }
    }
    CHECK(horizons > 500);
    CHECK(clear > 500);
}

TEST_CASE(
    "plane_range_near: the exact call's sign and value from a direction 1e-14 off, or NaN when too close",
    "[sampling][criteria]") {
    const glm::dvec3 o(1, -2, 3), p(4, 5, -6);
    const glm::dvec3 n = glm::normalize(glm::dvec3(0.3, -0.2, 1));
    int decided = 0, undecided = 0;
    for (int k = 0; k < 2000; ++k) {
        // Directions sweeping through the plane's horizon (n.d from about -0.9 to 0.9, and near 0).
        const double u = -1.2 + 2.4 * k / 1999.0;
        const glm::dvec3 d = glm::normalize(glm::dvec3(std::cos(u), std::sin(3 * u), u * (k % 7 ? 1 : 1e-7)));
        const glm::dvec3 d_off = d + glm::dvec3(1e-14, -1e-14, 1e-14);
        const double exact = detail::plane_range(o, p, n, d), near = detail::plane_range_near(o, p, n, d_off);
        if (std::isnan(near)) {
            ++undecided;
            CHECK(std::abs(glm::dot(n, d_off)) <= 1e-6);
            continue;
        }
        ++decided;
        REQUIRE((near < 0) == (exact < 0));
        if (exact > 0) CHECK(std::abs(near - exact) <= 1e-8 * exact);
    }
    CHECK(decided > 1900);
    CHECK(detail::plane_range_near(o, p, n, glm::dvec3(1, 0, 0)) == detail::plane_range(o, p, n, {1, 0, 0}));
    // Grazing (n.d = 1e-8) or a plane through the sonar: too close to call.
    const glm::dvec3 along = glm::normalize(glm::cross(n, glm::dvec3(1, 0, 0)));
    CHECK(std::isnan(detail::plane_range_near(o, p, n, glm::normalize(along + 1e-8 * n))));
    CHECK(std::isnan(detail::plane_range_near(o, o, n, glm::dvec3(0, 0, 1))));
    CHECK(detail::half_angle(0.25).s == std::sin(0.125));
    CHECK(detail::half_angle(0.25).c == std::cos(0.125));
}

TEST_CASE("recent_value: the last N results per thread, exact keys, zero a key like any other",
          "[criteria]") {
    int made = 0;
    auto half = [&](double w) {
        return recent_value<3>(w, [&](double x) {
            ++made;
            return x / 2;
        });
    };
    CHECK(half(0.0) == 0.0); // a zero key is made, not taken from an unused entry
    CHECK(made == 1);
    CHECK(half(0.3) == 0.15);
    CHECK(half(0.9) == 0.45);
    CHECK(half(0.3) == 0.15); // kept
    CHECK(made == 3);
    CHECK(half(std::nextafter(0.3, 1.0)) == std::nextafter(0.3, 1.0) / 2); // keys compare exactly
    CHECK(made == 4); // ... and it replaced the oldest (0)
    CHECK(half(0.0) == 0.0);
    CHECK(made == 5);
    CHECK(half(0.9) == 0.45); // replaced next: 0.3, not 0.9 (round robin)
    CHECK(half(0.3) == 0.15);
    CHECK(made == 6);
    const int before = made; // another thread has a store of its own: 0.3 is made there once
    std::thread([&] { half(0.3), half(0.3); }).join();
    CHECK(made == before + 1);
}

TEST_CASE("a cell's trend: the smaller one-sided slope where both agree, none at a crest, a step or an edge",
          "[sampling][criteria]") {
    const double bin = 0.01;
    auto node = [](double t, double per_metre_db, unsigned material = 1, double footprint_m = 0.05) {
        Node n;
        n.hit = Hit{t, {0, 0, 1}, material, 0, {0, 0, 1}};
        n.footprint_m = footprint_m, n.per_metre_db = per_metre_db;
        return n;
    };
    // Cells 5 cm long, 5 cm apart in range: one-sided slopes of 0.2 and 0.3 dB per 5 cm.
    std::vector<Node> ns = {node(1.00, 40.0), node(1.05, 40.2), node(1.10, 40.5)};
    const double smaller = adaptive::kLn10Over10 * 0.2 / 0.05; // d ln(echo per metre) / d range [1/m]
    CHECK(spread_slope(ns, 1, 1, bin) == Approx(smaller));
    CHECK(spread_slope(ns, 0, 1, bin) == 0); // the column's ends have one neighbour: none
    CHECK(spread_slope(ns, 2, 1, bin) == 0);
    std::vector<Node> x = ns;
    x[2].per_metre_db = 40.1; // a crest: the two slopes disagree in sign
    CHECK(spread_slope(x, 1, 1, bin) == 0);
    x[2].per_metre_db = 40.2 + 1.05 * kTrendStepDb; // a step: a kink or an edge, not a trend
    CHECK(spread_slope(x, 1, 1, bin) == 0);
    x[2].per_metre_db = 40.2 + 0.95 * kTrendStepDb;
    CHECK(spread_slope(x, 1, 1, bin) == Approx(smaller));
    x = ns;
    x[2] = node(1.10, 40.5, 2); // another material
    CHECK(spread_slope(x, 1, 1, bin) == 0);
    x[2] = node(1.30, 40.5); // further than the footprints reach: another surface behind
    CHECK(spread_slope(x, 1, 1, bin) == 0);
    x[2].hit.reset(); // a miss
    CHECK(spread_slope(x, 1, 1, bin) == 0);
    // Falling the other way: the smaller magnitude, its sign kept.
    const std::vector<Node> down = {node(1.00, 40.5), node(1.05, 40.2), node(1.10, 40.0)};
    CHECK(spread_slope(down, 1, 1, bin) == Approx(-smaller));
    // Cells within a bin: per_metre_db holds the echo per bin width; the same offset for each, so the same
    // trend.
    const std::vector<Node> small = {node(1.000, 40.0, 1, 0.005), node(1.005, 40.02, 1, 0.005),
                                     node(1.010, 40.05, 1, 0.005)};
    CHECK(spread_slope(small, 1, 1, bin) == Approx(adaptive::kLn10Over10 * 0.02 / 0.005));
    // Reach 3 (a merged triple's, from the neighbouring triples' middles): the range allowance scales.
    const std::vector<Node> far = {node(1.00, 40.0), node(1.05, 40.1), node(1.10, 40.2), node(1.15, 40.3),
                                   node(1.20, 40.4), node(1.25, 40.5), node(1.30, 40.6)};
    CHECK(spread_slope(far, 3, 3, bin) == Approx(adaptive::kLn10Over10 * 0.3 / 0.15));
}

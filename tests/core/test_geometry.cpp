// Embree first hits against a brute-force Moller-Trumbore reference in double over all triangles, with
// objects placed as instances (rotated, non-uniformly scaled, moved in place).
#include "support.hpp"

#include "core/base/errors.hpp"
#include "core/geometry/geometry.hpp"
#include "core/geometry/mesh.hpp"
#include "core/geometry/mesh_cache.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

using namespace sonarsim;

namespace {

struct Tri {
    glm::dvec3 v0, v1, v2;
    unsigned object, prim;
};

/// Writes `count` random triangles (own vertices each) inside [lo, hi]^3 as an OBJ; returns them.
std::vector<glm::vec3> write_random_obj(const std::string& path, std::mt19937& rng, int count, float lo,
                                        float hi) {
    std::uniform_real_distribution<float> u(lo, hi), small(-0.4f, 0.4f);
    std::vector<glm::vec3> v;
    FILE* f = std::fopen(path.c_str(), "w");
    REQUIRE(f);
    for (int t = 0; t < count; ++t) {
        const glm::vec3 c(u(rng), u(rng), u(rng)); // small triangles around a random centre
        for (int k = 0; k < 3; ++k) {
            v.push_back(c + glm::vec3(small(rng), small(rng), small(rng)));
            std::fprintf(f, "v %.9g %.9g %.9g\n", double(v.back().x), double(v.back().y), double(v.back().z));
        }
    }
    for (int t = 0; t < count; ++t) std::fprintf(f, "f %d %d %d\n", 3 * t + 1, 3 * t + 2, 3 * t + 3);
    std::fclose(f);
    return v;
}

/// Moller-Trumbore in double: t of the ray's crossing of the triangle's plane and its barycentrics u, v
/// (inside when u, v, 1 - u - v >= 0); NaN for a ray parallel to the plane.
double moller_trumbore(const glm::dvec3& o, const glm::dvec3& d, const Tri& tr, double& u, double& v) {
    const glm::dvec3 e1 = tr.v1 - tr.v0, e2 = tr.v2 - tr.v0, p = glm::cross(d, e2);
    const double det = glm::dot(e1, p);
    u = v = -1;
    if (std::abs(det) < 1e-300) return NAN;
    const glm::dvec3 s = o - tr.v0;
    u = glm::dot(s, p) / det;
    const glm::dvec3 q = glm::cross(s, e1);
    v = glm::dot(d, q) / det;
    return glm::dot(e2, q) / det;
}

struct BruteHit {
    bool hit = false, ambiguous = false;
    double t = 0;
    const Tri* tri = nullptr;
};

/// First hit over all triangles with t in (0, t_max]. `ambiguous` flags rays whose answer float arithmetic
/// may legitimately change: near a triangle's edge, near t_max, at grazing incidence, or with a second hit at
/// almost the same t.
BruteHit brute_force(const std::vector<Tri>& tris, const glm::dvec3& o, const glm::dvec3& d, double t_max) {
    BruteHit best;
    double second = INFINITY;
    const double edge_eps = 1e-4;
    for (const Tri& tr : tris) {
        double u, v;
        const double t = moller_trumbore(o, d, tr, u, v), inside = std::min({u, v, 1 - u - v});
        if (t > 0 && t <= t_max * (1 + 1e-5) && std::abs(inside) < edge_eps) best.ambiguous = true;
        if (inside < 0 || !(t > 0) || t > t_max) continue;
        if (!best.hit || t < best.t) {
            second = best.hit ? best.t : second;
            best.hit = true, best.t = t, best.tri = &tr;
        } else {
            second = std::min(second, t);
        }
    }
    if (best.hit && (second - best.t < 1e-4 * best.t || best.t > t_max * (1 - 1e-5))) best.ambiguous = true;
    // Grazing hits: float rounding of the ray moves t by (rounding / |cos|), too much for a 1e-4 check.
    if (best.hit) {
        const glm::dvec3 n = glm::cross(best.tri->v1 - best.tri->v0, best.tri->v2 - best.tri->v0);
        if (std::abs(glm::dot(d, glm::normalize(n))) < 0.01) best.ambiguous = true;
    }
    return best;
}

/// A unit ray direction from o: aimed at a random point of a random triangle (mostly hits), or random.
glm::dvec3 random_direction(std::mt19937& rng, const std::vector<Tri>& tris, const glm::dvec3& o,
                            bool aimed) {
    std::uniform_real_distribution<double> u(-1, 1);
    glm::dvec3 d;
    if (aimed) {
        const Tri& tr = tris[std::uniform_int_distribution<size_t>(0, tris.size() - 1)(rng)];
        double a = 0.5 * (u(rng) + 1), b = 0.5 * (u(rng) + 1);
        if (a + b > 1) a = 1 - a, b = 1 - b;
        d = tr.v0 + a * (tr.v1 - tr.v0) + b * (tr.v2 - tr.v0) - o;
    } else {
        do d = glm::dvec3(u(rng), u(rng), u(rng));
        while (glm::length(d) < 0.1 || glm::length(d) > 1);
    }
    return glm::normalize(d);
}

} // namespace

TEST_CASE("Embree first hits equal a brute-force ray-triangle reference", "[geometry]") {
    struct MeshSet {
        unsigned seed;
        std::vector<int> triangles_per_object;
    };
    const MeshSet sets[] = {{1u, {20}}, {7u, {200}}, {42u, {60, 90, 35}}, {2024u, {150, 5}}};
    int compared = 0, skipped = 0, hits = 0;
    for (const MeshSet& set : sets) {
        INFO("seed " << set.seed);
        std::mt19937 rng(set.seed);
        SceneDesc s;
        s.seafloor.reset();
        std::vector<Tri> tris;
        for (size_t m = 0; m < set.triangles_per_object.size(); ++m) {
            const std::string path =
                test::out_path("random_" + std::to_string(set.seed) + "_" + std::to_string(m) + ".obj");
            const std::vector<glm::vec3> v = write_random_obj(path, rng, set.triangles_per_object[m], -2, 2);
            for (int t = 0; t < set.triangles_per_object[m]; ++t)
                tris.push_back({glm::dvec3(v[3 * t]), glm::dvec3(v[3 * t + 1]), glm::dvec3(v[3 * t + 2]),
                                unsigned(m) + 1, unsigned(t)});
            ObjectDesc o;
            o.mesh = o.mesh_resolved = path;
            s.objects.push_back(o);
        }
        const SceneGeometry g(s);
        REQUIRE(g.has_meshes());
        REQUIRE(g.object_count() == set.triangles_per_object.size());
        for (size_t m = 0; m < g.object_count(); ++m)
            REQUIRE(g.local_mesh(m)->triangles.size() == size_t(set.triangles_per_object[m]));

        std::uniform_real_distribution<double> box(-4, 4), tm(0.5, 12);
        for (int r = 0; r < 4000; ++r) {
            const glm::dvec3 o(box(rng), box(rng), box(rng));
            const glm::dvec3 d = random_direction(rng, tris, o, r % 2 == 0);
            const double t_max = r % 3 == 0 ? tm(rng) : 100.0;
            const BruteHit ref = brute_force(tris, o, d, t_max);
            if (ref.ambiguous) {
                ++skipped;
                continue;
            }
            ++compared;
            const std::optional<Hit> h = g.intersect(o, d, t_max);
            INFO("ray " << r);
            REQUIRE(bool(h) == ref.hit);
            if (!ref.hit) continue;
            ++hits;
            CHECK(h->t == Approx(ref.t).epsilon(1e-4));
            CHECK(h->material == ref.tri->object);
            CHECK(h->prim == ref.tri->prim);
            const glm::dvec3 n =
                glm::normalize(glm::cross(ref.tri->v1 - ref.tri->v0, ref.tri->v2 - ref.tri->v0));
            CHECK(std::abs(glm::dot(h->normal, n)) == Approx(1.0).margin(1e-5));
            CHECK(glm::length(h->normal) == Approx(1.0).margin(1e-9));
        }
    }
    std::printf("Embree vs brute force: %d rays compared (%d hits), %d near-edge/near-tie rays skipped\n",
                compared, hits, skipped);
    CHECK(hits > 5000);
    CHECK(skipped < compared / 50);
}

TEST_CASE("box meshes have 12 outward triangles and the floor plane is hit from both sides", "[geometry]") {
    const TriMesh b = make_box({2, 4, 6});
    REQUIRE(b.triangles.size() == 12);
    for (const auto& t : b.triangles) {
        const glm::dvec3 v0(b.vertices[t.x]), v1(b.vertices[t.y]), v2(b.vertices[t.z]);
        const glm::dvec3 n = glm::cross(v1 - v0, v2 - v0), c = (v0 + v1 + v2) / 3.0;
        CHECK(glm::dot(n, c) > 0); // outward
    }
    Seafloor f;
    f.height_m = -1;
    const auto down = intersect_floor(f, {0, 0, 1}, glm::normalize(glm::dvec3(1, 0, -1)), 10);
    REQUIRE(down);
    CHECK(down->t == Approx(2 * std::sqrt(2.0)));
    CHECK(down->normal.z == 1.0);
    CHECK(down->material == kFloorMaterial);
    const auto up = intersect_floor(f, {0, 0, -3}, {0, 0, 1}, 10);
    REQUIRE(up);
    CHECK(up->t == Approx(2.0));
    CHECK_FALSE(intersect_floor(f, {0, 0, 1}, {0, 0, 1}, 10));                             // away from it
    CHECK_FALSE(intersect_floor(f, {0, 0, 1}, glm::normalize(glm::dvec3(1, 0, -1)), 2.5)); // beyond t_max
    CHECK_FALSE(intersect_floor(f, {0, 0, 1}, {1, 0, 0}, 10));                             // parallel
}

TEST_CASE("a placed box is hit where its rotated, scaled faces are", "[geometry]") {
    SceneDesc s;
    s.seafloor.reset();
    ObjectDesc o;
    o.box_m = Vec3d{1, 1, 1};
    o.scale = {2, 1, 1};            // 2 x 1 x 1 m
    o.orientation_deg = {0, 0, 90}; // yaw 90: its long side along y
    o.position_m = {5, 0, 0};
    s.objects.push_back(o);
    const SceneGeometry g(s);
    const auto h = g.intersect({0, 0, 0}, {1, 0, 0}, 100);
    REQUIRE(h);
    CHECK(h->t == Approx(4.5).epsilon(1e-6)); // short side (1 m) faces the ray
    CHECK(std::abs(h->normal.x) == Approx(1.0).margin(1e-6));
    const auto side = g.intersect({5, -10, 0}, {0, 1, 0}, 100);
    REQUIRE(side);
    CHECK(side->t == Approx(9.0).epsilon(1e-6)); // long side: 2 m along y
    CHECK_FALSE(g.intersect({0, 0, 0}, {1, 0, 0}, 4.4));
    CHECK_FALSE(g.intersect({0, 0, 2}, {1, 0, 0}, 100)); // passes above it
}

namespace {

/// The world triangles of every object of `g` (object i -> material i + 1), for the brute-force reference.
std::vector<Tri> world_triangles(const SceneGeometry& g) {
    std::vector<Tri> tris;
    for (size_t i = 0; i < g.object_count(); ++i) {
        const TriMesh w = g.world_mesh(i);
        for (size_t t = 0; t < w.triangles.size(); ++t)
            tris.push_back({glm::dvec3(w.vertices[w.triangles[t].x]),
                            glm::dvec3(w.vertices[w.triangles[t].y]),
                            glm::dvec3(w.vertices[w.triangles[t].z]), unsigned(i) + 1, unsigned(t)});
    }
    return tris;
}

/// Compares g's first hits with the brute-force reference on its world triangles for `rays` random rays;
/// returns the number of hits compared.
int compare_with_brute_force(const SceneGeometry& g, std::mt19937& rng, int rays) {
    const std::vector<Tri> tris = world_triangles(g);
    std::uniform_real_distribution<double> box(-8, 8);
    int hits = 0, skipped = 0;
    for (int r = 0; r < rays; ++r) {
        const glm::dvec3 o(box(rng), box(rng), box(rng));
        const glm::dvec3 d = random_direction(rng, tris, o, r % 2 == 0);
        const BruteHit ref = brute_force(tris, o, d, 100.0);
        if (ref.ambiguous) {
            ++skipped;
            continue;
        }
        const std::optional<Hit> h = g.intersect(o, d, 100.0);
        INFO("ray " << r);
        REQUIRE(bool(h) == ref.hit);
        if (!ref.hit) continue;
        ++hits;
        CHECK(h->t == Approx(ref.t).epsilon(1e-5));
        CHECK(h->material == ref.tri->object);
        CHECK(h->prim == ref.tri->prim);
        const glm::dvec3 n = glm::normalize(glm::cross(ref.tri->v1 - ref.tri->v0, ref.tri->v2 - ref.tri->v0));
        CHECK(glm::dot(h->normal, n) == Approx(1.0).margin(1e-5)); // same side as the world triangle's
        CHECK(glm::length(h->normal) == Approx(1.0).margin(1e-9));
    }
    CHECK(skipped < rays / 25);
    return hits;
}

/// Random placements: rotations all round, non-uniform scales from 0.3 to 3, positions within 3 m.
void place_randomly(SceneDesc& s, std::mt19937& rng) {
    std::uniform_real_distribution<double> angle(-180, 180), scale(0.3, 3), pos(-3, 3);
    for (ObjectDesc& o : s.objects) {
        o.orientation_deg = {angle(rng), angle(rng) / 2, angle(rng)};
        o.scale = {scale(rng), scale(rng), scale(rng)};
        o.position_m = {pos(rng), pos(rng), pos(rng)};
    }
}

} // namespace

TEST_CASE("instanced objects, rotated and non-uniformly scaled, hit like their world meshes", "[geometry]") {
    std::mt19937 rng(99);
    const std::string a = test::out_path("instanced_a.obj"), b = test::out_path("instanced_b.obj");
    write_random_obj(a, rng, 80, -1, 1);
    write_random_obj(b, rng, 40, -1, 1);
    SceneDesc s;
    s.seafloor.reset();
    for (const std::string* path : {&a, &b, &a}) { // a twice: two instances of one mesh
        ObjectDesc o;
        o.mesh = o.mesh_resolved = *path;
        s.objects.push_back(o);
    }
    ObjectDesc box;
    box.box_m = Vec3d{0.5, 1.0, 0.25};
    s.objects.push_back(box);
    int hits = 0;
    for (int placement = 0; placement < 4; ++placement) {
        place_randomly(s, rng);
        const SceneGeometry g(s);
        REQUIRE(g.object_count() == 4);
        CHECK(g.local_mesh(0).get() == g.local_mesh(2).get()); // one mesh, one BVH, two instances
        CHECK(g.local_mesh(0)->triangles.size() == 80);
        hits += compare_with_brute_force(g, rng, 1500);
        // The slab-test bounds hold every world vertex.
        for (size_t i = 0; i < g.object_count(); ++i)
            for (const glm::vec3& v : g.world_mesh(i).vertices)
                for (int k = 0; k < 3; ++k) {
                    CHECK(v[k] >= g.bounds_lo()[k]);
                    CHECK(v[k] <= g.bounds_hi()[k]);
                }
    }
    CHECK(hits > 2000);
}

TEST_CASE("update_transforms moves the instances: hits follow the new pose, nothing is reloaded",
          "[geometry]") {
    std::mt19937 rng(7);
    const std::string a = test::out_path("moved_a.obj");
    write_random_obj(a, rng, 60, -1, 1);
    SceneDesc s;
    s.seafloor.reset();
    ObjectDesc o;
    o.mesh = o.mesh_resolved = a;
    s.objects = {o, o};
    place_randomly(s, rng);
    SceneGeometry g(s);
    const TriMesh* mesh = g.local_mesh(0).get();
    const auto reads = MeshCache::global().files_read();

    SceneDesc moved = s;
    place_randomly(moved, rng);
    REQUIRE(g.update_transforms(moved));
    CHECK(g.local_mesh(0).get() == mesh);
    CHECK(MeshCache::global().files_read() == reads);
    CHECK(g.object_transform(1) == object_transform(moved.objects[1]));
    CHECK(compare_with_brute_force(g, rng, 2000) > 500);
    const SceneGeometry fresh(moved); // the same hits as a geometry built for the new pose
    for (int r = 0; r < 500; ++r) {
        std::uniform_real_distribution<double> u(-1, 1), box(-8, 8);
        const glm::dvec3 org(box(rng), box(rng), box(rng));
        const glm::dvec3 d = glm::normalize(glm::dvec3(u(rng), u(rng), u(rng)) - org / 8.0);
        const auto h1 = g.intersect(org, d, 100), h2 = fresh.intersect(org, d, 100);
        REQUIRE(bool(h1) == bool(h2));
        if (h1) CHECK((h1->t == h2->t && h1->prim == h2->prim && h1->material == h2->material));
    }

    // Other shapes: not an update; a placement beyond single precision: an error that changes nothing.
    SceneDesc other = moved;
    other.objects[1].box_m = Vec3d{1, 1, 1};
    CHECK_FALSE(g.update_transforms(other));
    other = moved;
    other.objects.pop_back();
    CHECK_FALSE(g.update_transforms(other));
    other = moved;
    other.objects[0].scale = {1e39, 1, 1};
    CHECK_THROWS_AS(g.update_transforms(other), InputError);
    CHECK(g.object_transform(0) == object_transform(moved.objects[0]));
    CHECK(compare_with_brute_force(g, rng, 500) > 100);
}

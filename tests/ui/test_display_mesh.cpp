// The 3D view's simplified meshes: within the triangle budget, close to the original surface, well formed.
#include "ui/model/display_mesh.hpp"

#include <catch2/catch.hpp>
#include <cmath>

using namespace sonarsim;

namespace {

/// A UV sphere of radius `r` [m] centred at `c`: 2 * nu * (nv - 1) triangles.
TriMesh sphere(int nu, int nv, float r, glm::vec3 c) {
    TriMesh m;
    m.vertices.push_back(c + glm::vec3(0, 0, r));
    for (int i = 1; i < nv; ++i)
        for (int j = 0; j < nu; ++j) {
            const float th = float(M_PI) * i / nv, ph = 2 * float(M_PI) * j / nu;
            m.vertices.push_back(
                c + r * glm::vec3(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)));
        }
    m.vertices.push_back(c - glm::vec3(0, 0, r));
    const auto v = [&](int i, int j) { return unsigned(1 + (i - 1) * nu + (j % nu)); };
    const unsigned last = unsigned(m.vertices.size() - 1);
    for (int j = 0; j < nu; ++j) m.triangles.emplace_back(0u, v(1, j), v(1, j + 1));
    for (int i = 1; i + 1 < nv; ++i)
        for (int j = 0; j < nu; ++j) {
            m.triangles.emplace_back(v(i, j), v(i + 1, j), v(i + 1, j + 1));
            m.triangles.emplace_back(v(i, j), v(i + 1, j + 1), v(i, j + 1));
        }
    for (int j = 0; j < nu; ++j) m.triangles.emplace_back(v(nv - 1, j), last, v(nv - 1, j + 1));
    return m;
}

void check_well_formed(const TriMesh& m) {
    for (const glm::uvec3& t : m.triangles) {
        REQUIRE(t.x < m.vertices.size());
        REQUIRE(t.y < m.vertices.size());
        REQUIRE(t.z < m.vertices.size());
        REQUIRE(t.x != t.y);
        REQUIRE(t.y != t.z);
        REQUIRE(t.x != t.z);
    }
}

} // namespace

TEST_CASE("a mesh within the budget is drawn as it is", "[ui][display_mesh]") {
    const TriMesh m = sphere(40, 20, 1, glm::vec3(0));
    const TriMesh d = ui::simplify_for_display(m, m.triangles.size());
    CHECK(d.vertices == m.vertices);
    CHECK(d.triangles == m.triangles);
}

TEST_CASE("a large mesh is clustered to the budget and keeps its shape", "[ui][display_mesh]") {
    const glm::vec3 centre(2, -1, 0.5f);
    const float r = 0.3f;
    const TriMesh m = sphere(500, 250, r, centre); // 249,000 triangles
    for (size_t budget : {size_t(30000), size_t(2000), size_t(100)}) {
        INFO("budget " << budget);
        const TriMesh d = ui::simplify_for_display(m, budget);
        CHECK(d.triangles.size() <= budget);
        CHECK(d.triangles.size() >= budget / 6); // not needlessly coarse
        check_well_formed(d);
        glm::vec3 lo, hi, mlo, mhi;
        REQUIRE(mesh_bounds(d, lo, hi));
        mesh_bounds(m, mlo, mhi);
        // Clustered vertices are means of nearby vertices: on or just inside the sphere.
        const float cell = std::sqrt(4 * float(M_PI) * r * r * 3 / float(budget)) * 2;
        for (const glm::vec3& p : d.vertices) {
            CHECK(glm::length(p - centre) <= r * 1.0001f);
            CHECK(glm::length(p - centre) >= r - cell);
        }
        CHECK(glm::length(lo - mlo) < 2 * cell);
        CHECK(glm::length(hi - mhi) < 2 * cell);
    }
}

TEST_CASE("several meshes share the budget by size", "[ui][display_mesh]") {
    const std::vector<std::shared_ptr<const TriMesh>> meshes = {
        std::make_shared<const TriMesh>(sphere(400, 200, 1, glm::vec3(0))),
        std::make_shared<const TriMesh>(sphere(100, 50, 1, glm::vec3(5, 0, 0))),
        std::make_shared<const TriMesh>(sphere(8, 4, 1, glm::vec3(-5, 0, 0)))};
    const auto d = ui::simplify_for_display(meshes, 20000);
    REQUIRE(d.size() == 3);
    size_t total = 0;
    for (const auto& m : d) total += m->triangles.size(), check_well_formed(*m);
    CHECK(total <= 20000);
    CHECK(d[0]->triangles.size() < meshes[0]->triangles.size());
    CHECK(d[0]->triangles.size() > 20000 / 4);
    CHECK(d[1] == meshes[1]); // within their equal shares: kept whole, the same mesh
    CHECK(d[2] == meshes[2]);
}

#include "ui/model/display_mesh.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <unordered_set>

namespace sonarsim::ui {
namespace {

/// Vertex clustering with cubic cells of size `cell` [m] starting at `lo`.
TriMesh cluster(const TriMesh& m, glm::dvec3 lo, double cell) {
    // Cell of every vertex, numbered in order of first appearance.
    std::unordered_map<std::uint64_t, std::uint32_t> cell_id;
    cell_id.reserve(m.vertices.size() / 4 + 16);
    std::vector<std::uint32_t> vertex_cell(m.vertices.size());
    std::vector<glm::dvec3> sum;
    std::vector<std::uint32_t> count;
    for (size_t v = 0; v < m.vertices.size(); ++v) {
        const glm::dvec3 q = (glm::dvec3(m.vertices[v]) - lo) / cell;
        const auto c = [](double x) { return std::uint64_t(std::clamp(x, 0.0, 2097151.0)); }; // 21 bits
        const std::uint64_t key = c(q.x) | c(q.y) << 21 | c(q.z) << 42;
        const auto [it, added] = cell_id.emplace(key, std::uint32_t(sum.size()));
        if (added) sum.emplace_back(0.0), count.push_back(0);
        vertex_cell[v] = it->second;
        sum[it->second] += glm::dvec3(m.vertices[v]);
        ++count[it->second];
    }
    TriMesh out;
    out.vertices.resize(sum.size());
    for (size_t c = 0; c < sum.size(); ++c) out.vertices[c] = glm::vec3(sum[c] / double(count[c]));
    // Triangles whose corners fall in three different cells, each once (whatever its orientation).
    std::unordered_set<std::uint64_t> seen;
    seen.reserve(m.triangles.size() / 2 + 16);
    const bool small = sum.size() < (1u << 21);
    for (const glm::uvec3& t : m.triangles) {
        const std::uint32_t a = vertex_cell[t.x], b = vertex_cell[t.y], c = vertex_cell[t.z];
        if (a == b || b == c || a == c) continue;
        if (small) { // remove duplicates; beyond 2^21 cells duplicates are rare and harmless
            std::array<std::uint64_t, 3> k{a, b, c};
            std::sort(k.begin(), k.end());
            if (!seen.insert(k[0] | k[1] << 21 | k[2] << 42).second) continue;
        }
        out.triangles.emplace_back(a, b, c);
    }
    return out;
}

} // namespace

TriMesh simplify_for_display(const TriMesh& mesh, std::size_t max_triangles) {
    if (mesh.triangles.size() <= max_triangles) return mesh;
    glm::vec3 lo, hi;
    if (!mesh_bounds(mesh, lo, hi)) return mesh;
    const double extent = std::max(1e-9, double(glm::length(hi - lo)));
    // A clustered surface has about two triangles per occupied cell, and a surface of area A occupies
    // about 1.5 A / cell^2 cells: start there, then grow the cell until the result fits.
    double area = 0;
    for (const glm::uvec3& t : mesh.triangles) {
        const glm::dvec3 a(mesh.vertices[t.x]), b(mesh.vertices[t.y]), c(mesh.vertices[t.z]);
        area += 0.5 * glm::length(glm::cross(b - a, c - a));
    }
    double cell =
        std::max(extent / 2000000.0, std::sqrt(3.0 * area / double(std::max<size_t>(1, max_triangles))));
    for (;;) {
        TriMesh out = cluster(mesh, glm::dvec3(lo), cell);
        if (out.triangles.size() <= max_triangles) return out;
        cell *= std::max(1.05, std::sqrt(double(out.triangles.size()) / double(max_triangles)));
    }
}

std::vector<std::shared_ptr<const TriMesh>>
simplify_for_display(const std::vector<std::shared_ptr<const TriMesh>>& meshes, std::size_t max_triangles) {
    // Fair shares, smallest mesh first: one within its share keeps all of it and leaves the rest to others.
    std::vector<size_t> order(meshes.size()), budget(meshes.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(),
              [&](size_t a, size_t b) { return meshes[a]->triangles.size() < meshes[b]->triangles.size(); });
    size_t left = max_triangles;
    for (size_t k = 0; k < order.size(); ++k) {
        const size_t i = order[k], share = left / (order.size() - k);
        budget[i] = std::min(meshes[i]->triangles.size(), share);
        left -= budget[i];
    }
    std::vector<std::shared_ptr<const TriMesh>> out;
    out.reserve(meshes.size());
    for (size_t i = 0; i < meshes.size(); ++i)
        out.push_back(budget[i] >= meshes[i]->triangles.size()
                          ? meshes[i]
                          : std::make_shared<const TriMesh>(simplify_for_display(*meshes[i], budget[i])));
    return out;
}

} // namespace sonarsim::ui

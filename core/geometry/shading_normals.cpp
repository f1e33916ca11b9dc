#include "core/geometry/shading_normals.hpp"

#include "core/base/shared_registry.hpp"

#include "core/data/pose.hpp"

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <cmath>
#include <map>
#include <mutex>
#include <numeric>
#include <tuple>
#include <utility>

namespace sonarsim {
namespace {

/// Each vertex's representative among the vertices at exactly its position (the lowest index), so that
/// meshes with split vertices (STL: three per triangle) smooth across their shared edges.
std::vector<unsigned> welded_vertices(const TriMesh& m) {
    std::vector<unsigned> order(m.vertices.size());
    std::iota(order.begin(), order.end(), 0u);
    const auto& v = m.vertices;
    tbb::parallel_sort(order.begin(), order.end(), [&](unsigned a, unsigned b) {
        return std::tie(v[a].x, v[a].y, v[a].z, a) < std::tie(v[b].x, v[b].y, v[b].z, b);
    });
    std::vector<unsigned> rep(v.size());
    for (size_t i = 0; i < order.size(); ++i)
        rep[order[i]] = (i > 0 && v[order[i]] == v[order[i - 1]]) ? rep[order[i - 1]] : order[i];
    return rep;
}

} // namespace

ShadingNormals corner_normals(const TriMesh& m, double crease_angle_deg) {
    ShadingNormals out;
    out.crease_angle_deg = crease_angle_deg;
    if (!(crease_angle_deg > 0) || m.triangles.empty()) return out;
    const size_t T = m.triangles.size();
    const double cos_crease = std::cos(deg2rad(std::min(crease_angle_deg, 180.0)));

    // Unit face normals (zero for a degenerate face) and each corner's angle.
    std::vector<glm::dvec3> face(T);
    std::vector<double> angle(3 * T, 0.0);
    tbb::parallel_for(size_t(0), T, [&](size_t t) {
        const glm::uvec3 tri = m.triangles[t];
        const glm::dvec3 p[3] = {m.vertices[tri.x], m.vertices[tri.y], m.vertices[tri.z]};
        const glm::dvec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
        const double len = glm::length(n);
        if (!(len > 0)) return; // degenerate: takes no part
        face[t] = n / len;
        for (int k = 0; k < 3; ++k) {
            const glm::dvec3 a = p[(k + 1) % 3] - p[k], b = p[(k + 2) % 3] - p[k];
            angle[3 * t + size_t(k)] = std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
        }
    });

    // The corners around each (welded) vertex, as compressed rows.
    const std::vector<unsigned> rep = welded_vertices(m);
    std::vector<size_t> start(m.vertices.size() + 1, 0);
    for (const glm::uvec3& tri : m.triangles)
        for (int k = 0; k < 3; ++k) ++start[rep[tri[k]] + 1];
    std::partial_sum(start.begin(), start.end(), start.begin());
    std::vector<size_t> fill(start.begin(), start.end() - 1);
    std::vector<unsigned> corners_at(3 * T); // corner index 3 t + k
    for (size_t t = 0; t < T; ++t)
        for (int k = 0; k < 3; ++k) corners_at[fill[rep[m.triangles[t][k]]]++] = unsigned(3 * t + size_t(k));

    // Where the faces around a vertex all lie within half the crease angle (less a margin far above rounding)
    // of one direction, every pair of them lies within the crease angle, so every corner there sums all of
    // them: one sum per vertex, in the order the per-corner loop below adds them (the same bits), instead of
    // one per corner. Other vertices (creases, near-180-degree crease angles) take the per-corner loop.
    const double half = 0.5 * deg2rad(std::min(crease_angle_deg, 180.0)) - 1e-6;
    const bool cone_test = half > 1e-6 && crease_angle_deg < 179;
    const double cos_half = std::cos(half);
    std::vector<glm::dvec3> vertex_normal(cone_test ? m.vertices.size() : 0);
    std::vector<unsigned char> one_sum(cone_test ? m.vertices.size() : 0, 0);
    if (cone_test)
        tbb::parallel_for(size_t(0), m.vertices.size(), [&](size_t v) {
            if (start[v] == start[v + 1]) return;
            glm::dvec3 mean(0), sum(0);
            for (size_t i = start[v]; i < start[v + 1]; ++i) mean += face[corners_at[i] / 3];
            const double len = glm::length(mean);
            if (!(len > 0)) return;
            mean /= len;
            for (size_t i = start[v]; i < start[v + 1]; ++i) {
                const unsigned c = corners_at[i];
                const glm::dvec3& ng = face[c / 3];
                if (ng == glm::dvec3(0)) continue; // degenerate: adds nothing either way
                if (!(glm::dot(mean, ng) >= cos_half)) return;
                sum += angle[c] * ng;
            }
            vertex_normal[v] = sum, one_sum[v] = 1;
        });

    out.corner.assign(3 * T, glm::vec3(0));
    std::vector<unsigned char>& bent = out.bent; // a corner normal differs from its face normal
    bent.assign(T, 0);
    tbb::parallel_for(size_t(0), T, [&](size_t t) {
        const glm::dvec3 nf = face[t];
        if (nf == glm::dvec3(0)) return;
        for (int k = 0; k < 3; ++k) {
            const unsigned v = rep[m.triangles[t][k]];
            glm::dvec3 sum(0);
            if (cone_test && one_sum[v]) {
                sum = vertex_normal[v];
            } else {
                for (size_t i = start[v]; i < start[v + 1]; ++i) {
                    const unsigned c = corners_at[i];
                    const glm::dvec3& ng = face[c / 3];
                    if (glm::dot(nf, ng) >= cos_crease) sum += angle[c] * ng;
                }
            }
            const double len = glm::length(sum);
            const glm::dvec3 n = len > 0 ? sum / len : nf;
            out.corner[3 * t + size_t(k)] = glm::vec3(n);
            if (1 - glm::dot(n, nf) > 1e-12) bent[t] = 1;
        }
    });
    // Nothing bent (a box, or a crease angle below every dihedral angle): the face normals, exactly as Embree
    // reports them, and no memory.
    if (std::find(bent.begin(), bent.end(), 1) == bent.end()) out.corner = {}, out.bent = {};
    return out;
}

namespace {} // namespace

std::shared_ptr<const ShadingNormals> shared_corner_normals(const std::shared_ptr<const TriMesh>& mesh,
                                                            double crease_angle_deg) {
    if (!mesh || !(crease_angle_deg > 0)) return nullptr;
    // The corner normals in use, one per (mesh, crease angle): computed by the first to ask, shared while
    // anything holds them (they keep their mesh alive, so a mesh's address names one mesh).
    static SharedRegistry<std::pair<const TriMesh*, double>, ShadingNormals> registry;
    return registry.get({mesh.get(), crease_angle_deg}, [&] {
        auto n = std::make_shared<ShadingNormals>(corner_normals(*mesh, crease_angle_deg));
        n->mesh = mesh;
        return std::shared_ptr<const ShadingNormals>(std::move(n));
    });
}

} // namespace sonarsim

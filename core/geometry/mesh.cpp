// load_mesh dispatches by the format table (mesh_formats.hpp); the readers are in mesh_obj.cpp,
// mesh_ply.cpp, mesh_stl.cpp, mesh_off.cpp and openmesh_import.cpp.
#include "core/geometry/mesh.hpp"

#include "core/base/errors.hpp"
#include "core/base/file_io.hpp"
#include "core/data/pose.hpp"
#include "core/meshfile/mesh_formats.hpp"
#include "core/meshfile/mesh_tokens.hpp"

#include <cmath>
#include <filesystem>

namespace sonarsim {

TriMesh load_mesh(const std::string& path, const std::string& scene_file, const std::string& key) {
    const std::string where = "mesh \"" + path + "\"";
    const MeshFormat* format = find_mesh_format(path);
    if (!format)
        throw InputError(scene_file, key,
                         where + ": unknown extension \"" + mesh_extension_of(path) +
                             "\"; allowed: " + mesh_extensions_text());
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw InputError(scene_file, key, where + ": file not found");
    if (!std::filesystem::is_regular_file(path, ec))
        throw InputError(scene_file, key, where + ": not a regular file");
    const std::string bytes = read_file_bytes(path, kAnyFileSize, {scene_file, key, where + ": ", ""});
    if (bytes.empty()) throw InputError(scene_file, key, where + ": file is empty");

    TriMesh out;
    try {
        out = format->read({path, bytes});
    } catch (const mesh_io::Problem& p) {
        throw InputError(scene_file, key,
                         where + (p.line > 0 ? ", line " + std::to_string(p.line) : "") + ": " + p.message);
    } catch (const std::exception& e) { // e.g. std::bad_alloc from a reader
        throw InputError(scene_file, key, where + ": cannot be loaded: " + e.what());
    }
    for (size_t i = 0; i < out.vertices.size(); ++i) {
        const glm::vec3& v = out.vertices[i];
        if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
            throw InputError(scene_file, key,
                             where + ": vertex " + std::to_string(i) + " has a non-finite coordinate");
    }
    if (out.triangles.empty()) throw InputError(scene_file, key, where + ": contains no faces");
    return out;
}

TriMesh make_box(const Vec3d& s) {
    TriMesh m;
    const float hx = float(s[0] / 2), hy = float(s[1] / 2), hz = float(s[2] / 2);
    for (int i = 0; i < 8; ++i) m.vertices.emplace_back(i & 1 ? hx : -hx, i & 2 ? hy : -hy, i & 4 ? hz : -hz);
    const unsigned quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                  {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (auto& q : quads) {
        m.triangles.emplace_back(q[0], q[1], q[2]);
        m.triangles.emplace_back(q[0], q[2], q[3]);
    }
    return m;
}

glm::dmat4 object_transform(const ObjectDesc& o) {
    glm::dmat3 S(1.0);
    for (int k = 0; k < 3; ++k) S[k][k] = o.scale[size_t(k)];
    glm::dmat4 m(rotation_matrix(o.orientation_deg) * S);
    m[3] = glm::dvec4(to_glm(o.position_m), 1.0);
    return m;
}

void check_single_precision(const glm::dvec3& world, const std::string& scene_file, const std::string& key) {
    const glm::vec3 v(world);
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
        throw InputError(scene_file, key + ".scale",
                         "scaled and placed, the object's coordinates exceed single precision; use a smaller "
                         "scale");
}

TriMesh transformed_mesh(const TriMesh& mesh, const glm::dmat4& transform, const std::string& scene_file,
                         const std::string& key) {
    TriMesh m = mesh;
    for (auto& v : m.vertices) {
        const glm::dvec3 w(transform * glm::dvec4(glm::dvec3(v), 1.0));
        check_single_precision(w, scene_file, key);
        v = glm::vec3(w);
    }
    return m;
}

bool mesh_bounds(const TriMesh& m, glm::vec3& lo, glm::vec3& hi) {
    if (m.vertices.empty()) return false;
    lo = hi = m.vertices[0];
    for (auto& v : m.vertices) lo = glm::min(lo, v), hi = glm::max(hi, v);
    return true;
}

} // namespace sonarsim

#include "mesh.hpp"

#include "errors.hpp"
#include "pose.hpp"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

namespace sonarsim {
namespace {

using OMesh = OpenMesh::PolyMesh_ArrayKernelT<>;

std::string lower_extension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

} // namespace

TriMesh load_mesh(const std::string& path, const std::string& scene_file, const std::string& key) {
    const std::string where = "mesh \"" + path + "\"";
    const std::string ext = lower_extension(path);
    if (ext != ".obj" && ext != ".ply" && ext != ".stl" && ext != ".off")
        throw InputError(scene_file, key,
                         where + ": unknown extension \"" + ext + "\"; allowed: .obj, .ply, .stl, .off");
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw InputError(scene_file, key, where + ": file not found");
    if (!std::filesystem::is_regular_file(path, ec))
        throw InputError(scene_file, key, where + ": not a regular file");
    if (!std::ifstream(path).good()) throw InputError(scene_file, key, where + ": cannot be read");
    if (std::filesystem::file_size(path, ec) == 0)
        throw InputError(scene_file, key, where + ": file is empty");

    OMesh om;
    OpenMesh::IO::Options opt;
    omerr().disable();
    omlog().disable();
    const bool ok = OpenMesh::IO::read_mesh(om, path, opt);
    if (!ok) throw InputError(scene_file, key, where + ": not a valid " + ext.substr(1) + " mesh");

    TriMesh out;
    out.vertices.reserve(om.n_vertices());
    for (auto vh : om.vertices()) {
        const auto& p = om.point(vh);
        if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
            throw InputError(scene_file, key,
                             where + ": vertex " + std::to_string(vh.idx()) + " has a non-finite coordinate");
        out.vertices.emplace_back(p[0], p[1], p[2]);
    }
    for (auto fh : om.faces()) {
        std::vector<unsigned> idx;
        for (auto vh : om.fv_range(fh)) idx.push_back(unsigned(vh.idx()));
        for (size_t k = 1; k + 1 < idx.size(); ++k) out.triangles.emplace_back(idx[0], idx[k], idx[k + 1]);
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

TriMesh object_world_mesh(const ObjectDesc& o, const std::string& scene_file, const std::string& key) {
    TriMesh m = o.box_m ? make_box(*o.box_m) : load_mesh(o.mesh_resolved, scene_file, key + ".mesh");
    const glm::dmat3 R = rotation_matrix(o.orientation_deg);
    const glm::dvec3 t = to_glm(o.position_m), s = to_glm(o.scale);
    for (auto& v : m.vertices) v = glm::vec3(R * (s * glm::dvec3(v)) + t);
    return m;
}

bool mesh_bounds(const TriMesh& m, glm::vec3& lo, glm::vec3& hi) {
    if (m.vertices.empty()) return false;
    lo = hi = m.vertices[0];
    for (auto& v : m.vertices) lo = glm::min(lo, v), hi = glm::max(hi, v);
    return true;
}

} // namespace sonarsim

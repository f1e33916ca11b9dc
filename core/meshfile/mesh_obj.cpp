#include "core/meshfile/mesh_readers.hpp"

#include "core/meshfile/mesh_tokens.hpp"

#include <set>
#include <sstream>
#include <vector>

namespace sonarsim::mesh_io {
namespace {

/// An OBJ index ("3", "-1") into `count` elements defined so far, as 1-based; 0 when out of range.
long long obj_index(const std::string& token, long long count) {
    long long i = 0;
    if (!integer(token, i)) return -1;
    const long long resolved = i < 0 ? count + i + 1 : i;
    return i == 0 || resolved < 1 || resolved > count ? 0 : resolved;
}

} // namespace

Expect check_obj(const std::string& text) {
    // Comments only as whole lines: OpenMesh reads "f 1 2 3 # x" as corners, and asserts (aborts) on a face
    // without any corner it can read.
    TextLines lines(text, false);
    std::vector<std::string> t;
    long long vertices = 0, texcoords = 0, normals = 0, faces = 0;
    const char* const counting = " defined before this line (indices start at 1; negative ones count back)";
    while (lines.next(t)) {
        if (t[0] == "v") {
            if (t.size() < 4 || !finite_float(t[1]) || !finite_float(t[2]) || !finite_float(t[3]))
                fail("vertex needs 3 finite coordinates (single precision), got " +
                         show(t.size() < 4 ? "" : t[1] + " " + t[2] + " " + t[3]),
                     lines.line());
            ++vertices;
        } else if (t[0] == "vt") {
            ++texcoords;
        } else if (t[0] == "vn") {
            ++normals;
        } else if (t[0] == "f") {
            if (t.size() < 4) fail("a face needs at least 3 corners", lines.line());
            std::set<long long> corners;
            for (size_t k = 1; k < t.size(); ++k) {
                // v, v/vt, v//vn or v/vt/vn; every index given must exist.
                std::vector<std::string> part;
                std::stringstream corner(t[k]);
                for (std::string p; std::getline(corner, p, '/');) part.push_back(p);
                if (part.empty() || part.size() > 3 || (t[k].back() == '/'))
                    fail("face corner " + show(t[k]) + " is not v, v/vt, v//vn or v/vt/vn", lines.line());
                long long i = 0;
                if (!integer(part[0], i))
                    fail("face corner " + show(t[k]) + " does not start with a vertex index", lines.line());
                const long long v = obj_index(part[0], vertices);
                if (v == 0)
                    fail("face refers to vertex " + part[0] + " but " + std::to_string(vertices) +
                             " vertices are" + counting,
                         lines.line());
                if (part.size() > 1 && !part[1].empty() && obj_index(part[1], texcoords) <= 0)
                    fail("face refers to texture coordinate " + show(part[1]) + " but " +
                             std::to_string(texcoords) + " are" + counting,
                         lines.line());
                if (part.size() > 2 && obj_index(part[2], normals) <= 0)
                    fail("face refers to normal " + show(part[2]) + " but " + std::to_string(normals) +
                             " are" + counting,
                         lines.line());
                corners.insert(v);
            }
            if (corners.size() >= 3 && corners.size() != t.size() - 1)
                fail("face repeats a vertex", lines.line());
            if (corners.size() >= 3) ++faces; // fewer: a point or a line, no area; OpenMesh skips it
        }
    }
    return {faces, "", false};
}

TriMesh read_obj(const MeshFile& file) {
    return read_with_openmesh(file, ".obj", check_obj(file.bytes));
}

} // namespace sonarsim::mesh_io

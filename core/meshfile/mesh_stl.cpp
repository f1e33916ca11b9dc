#include "core/meshfile/mesh_readers.hpp"

#include "core/meshfile/mesh_tokens.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

namespace sonarsim::mesh_io {
namespace {

bool starts_with_solid(const std::string& bytes) {
    const size_t p = bytes.find_first_not_of(" \t\r\n");
    return p != std::string::npos && bytes.compare(p, 5, "solid") == 0;
}

} // namespace

Expect check_stl(const std::string& bytes) {
    const size_t size = bytes.size();
    if (size >= 84) {
        std::uint32_t n = 0;
        for (int b = 0; b < 4; ++b)
            n |= std::uint32_t(static_cast<unsigned char>(bytes[size_t(80 + b)])) << (8 * b);
        // OpenMesh's rule: binary when the size matches the triangle count exactly, otherwise ASCII.
        if (84 + 50 * std::uint64_t(n) == size) {
            for (std::uint32_t i = 0; i < n; ++i)
                for (int c = 0; c < 9; ++c) {
                    float x;
                    std::memcpy(&x, bytes.data() + 84 + 50 * size_t(i) + 12 + 4 * c,
                                4); // little-endian hosts
                    if (!std::isfinite(x))
                        fail("triangle " + std::to_string(i) + " has a non-finite vertex coordinate");
                }
            // OpenMesh skips triangles with two equal corners (no area), so no face count to compare.
            return {};
        }
        if (!starts_with_solid(bytes) || !text_like(bytes))
            fail("binary STL: the header declares " + std::to_string(n) +
                 " triangles, which take 84 + 50 x " + std::to_string(n) + " = " +
                 std::to_string(84 + 50 * std::uint64_t(n)) + " bytes, but the file has " +
                 std::to_string(size) + " (truncated, or the count is wrong)");
    } else if (!starts_with_solid(bytes) || !text_like(bytes)) {
        fail("too short for a binary STL (" + std::to_string(size) +
             " bytes, the header alone takes 84) and not "
             "an ASCII STL (\"solid ...\")");
    }
    // ASCII STL: count facets, check every vertex line, and require the closing endsolid.
    TextLines lines(bytes, false);
    std::vector<std::string> t;
    long long facets = 0, vertices = 0;
    std::string last;
    while (lines.next(t)) {
        last = t[0];
        if (t[0] == "facet") {
            if (vertices != 3 * facets)
                fail("facet " + std::to_string(facets) + " does not have 3 vertices", lines.line());
            ++facets;
        } else if (t[0] == "vertex") {
            if (t.size() != 4 || !finite_float(t[1]) || !finite_float(t[2]) || !finite_float(t[3]))
                fail("vertex needs 3 finite coordinates (single precision)", lines.line());
            ++vertices;
        }
    }
    if (last != "endsolid") fail("ASCII STL is truncated: it does not end with \"endsolid\"");
    if (vertices != 3 * facets) fail("facet " + std::to_string(facets - 1) + " does not have 3 vertices");
    return {}; // OpenMesh skips triangles with two equal corners (no area): no face count to compare
}

TriMesh read_stl(const MeshFile& file) {
    return read_with_openmesh(file, ".stl", check_stl(file.bytes));
}

} // namespace sonarsim::mesh_io

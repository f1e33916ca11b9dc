#include "core/meshfile/mesh_readers.hpp"

#include "core/meshfile/mesh_tokens.hpp"

#include <cstdlib>
#include <set>
#include <vector>

namespace sonarsim::mesh_io {

// ---- OFF ----
// Read here, not by OpenMesh: its OFF reader takes a face's corner count from wherever its token stream
// happens to be, so a stray byte can make it allocate gigabytes (fuzzing found several). OFF is simple enough
// to read in full: "OFF" (or COFF, NOFF, STOFF...), the counts, one vertex per line (x y z, then colour or
// normal values, ignored), one face per line (k i1 .. ik, then an optional colour, ignored); # starts a
// comment.

TriMesh read_off(const MeshFile& file) {
    const std::string& text = file.bytes;
    TextLines lines(text, true);
    std::vector<std::string> t;
    if (!lines.next(t)) fail("empty OFF file");
    const std::string magic = t[0];
    const size_t off = magic.rfind("OFF");
    if (off == std::string::npos || off + 3 != magic.size() ||
        magic.substr(0, off).find_first_not_of("STCN") != std::string::npos)
        fail("first line must be OFF (or STOFF, COFF, NOFF, CNOFF...; 3D only), got " + show(magic),
             lines.line());
    if (t.size() > 1 && t[1] == "BINARY") fail("binary OFF is not supported; use ASCII OFF, PLY or STL");
    std::vector<std::string> counts(t.begin() + 1, t.end());
    if (counts.empty() && !lines.next(counts)) fail("truncated: the vertex and face counts are missing");
    long long nv = 0, nf = 0;
    if (counts.size() < 2 || !integer(counts[0], nv) || !integer(counts[1], nf) || nv < 0 || nf < 0)
        fail("expected the counts \"vertices faces edges\", got " + show(counts.empty() ? "" : counts[0]),
             lines.line());
    // Every vertex takes at least 6 bytes ("0 0 0\n"), every face at least 2: reject lying counts before
    // anything is allocated.
    if (double(nv) * 6 + double(nf) * 2 > double(text.size()))
        fail("truncated: the header declares " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
             " faces, more than the file's " + std::to_string(text.size()) + " bytes can hold");
    const std::string declared =
        " (the header declares " + std::to_string(nv) + " vertices and " + std::to_string(nf) + " faces)";
    TriMesh mesh;
    mesh.vertices.reserve(size_t(nv));
    for (long long v = 0; v < nv; ++v) {
        if (!lines.next(t))
            fail("truncated: the file ends after " + std::to_string(v) + " vertices" + declared);
        if (t.size() < 3 || !finite_float(t[0]) || !finite_float(t[1]) || !finite_float(t[2]))
            fail("vertex " + std::to_string(v) + " needs 3 finite coordinates (single precision), got " +
                     show(t[0]),
                 lines.line());
        mesh.vertices.emplace_back(std::strtof(t[0].c_str(), nullptr), std::strtof(t[1].c_str(), nullptr),
                                   std::strtof(t[2].c_str(), nullptr));
    }
    for (long long f = 0; f < nf; ++f) {
        if (!lines.next(t)) fail("truncated: the file ends after " + std::to_string(f) + " faces" + declared);
        long long k = 0;
        if (!integer(t[0], k) || k < 0 || k > (long long)t.size() - 1)
            fail("face " + std::to_string(f) + ": the corner count " + show(t[0]) +
                     " is not followed by that many vertex indices on its line",
                 lines.line());
        std::vector<unsigned> corners;
        for (long long c = 1; c <= k; ++c) {
            long long i = 0;
            if (!integer(t[size_t(c)], i) || i < 0 || i >= nv)
                fail("face " + std::to_string(f) + " refers to vertex " + show(t[size_t(c)]) +
                         "; allowed: 0 to " + std::to_string(nv - 1),
                     lines.line());
            corners.push_back(unsigned(i));
        }
        const size_t distinct = std::set<unsigned>(corners.begin(), corners.end()).size();
        if (distinct < 3) continue; // a point or a line: no area, no echo
        if (distinct != corners.size()) fail("face " + std::to_string(f) + " repeats a vertex", lines.line());
        for (size_t c = 1; c + 1 < corners.size(); ++c)
            mesh.triangles.emplace_back(corners[0], corners[c], corners[c + 1]);
    }
    return mesh;
}

} // namespace sonarsim::mesh_io

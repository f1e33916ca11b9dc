#include "core/meshfile/mesh_readers.hpp"

#include "core/meshfile/mesh_tokens.hpp"

#include <cstdint>
#include <sstream>
#include <vector>

namespace sonarsim::mesh_io {
namespace {

struct PlyProperty {
    int count_size = 0; ///< bytes of a list's count (0: not a list)
    bool count_signed = false;
    int size = 0;        ///< bytes of the value or of each list item
    bool real = false;   ///< the value or the items are float or double
    bool as_int = false; ///< OpenMesh reads it into an integer (colours, vertex indices)
};
struct PlyElement {
    std::string name;
    long long count = 0;
    std::vector<PlyProperty> properties;
};

int ply_type_size(const std::string& type, bool& is_signed) {
    is_signed = !(type[0] == 'u');
    if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
    if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
    if (type == "int" || type == "uint" || type == "int32" || type == "uint32") return 4;
    if (type == "float" || type == "float32") return 4;
    if (type == "double" || type == "float64") return 8;
    return 0;
}

long long ply_read_count(const unsigned char* p, int size, bool is_signed, bool big_endian) {
    std::uint64_t u = 0;
    for (int b = 0; b < size; ++b) u |= std::uint64_t(p[big_endian ? size - 1 - b : b]) << (8 * b);
    if (is_signed && size < 8 && (u >> (8 * size - 1)) & 1) return -1; // negative
    return (long long)u;
}

} // namespace

Expect check_ply(const std::string& bytes) {
    // The header, line by line and strictly: OpenMesh's PLY reader loops forever on some malformed headers.
    std::vector<PlyElement> elements;
    std::string format, hint;
    bool ascii_format = false, faces_seen = false; // faces_seen: the face element is complete
    size_t pos = 0, body = std::string::npos;
    for (long line = 1; pos < bytes.size() && body == std::string::npos; ++line) {
        size_t eol = bytes.find('\n', pos);
        if (eol == std::string::npos) fail("truncated: the header has no end_header line");
        std::istringstream in(bytes.substr(pos, eol - pos));
        pos = eol + 1;
        std::vector<std::string> t;
        for (std::string w; in >> w;) t.push_back(w);
        if (line == 1) {
            if (t.size() != 1 || t[0] != "ply") fail("not a PLY file (the first line must be \"ply\")");
        } else if (line == 2) {
            if (t.size() != 3 || t[0] != "format" || t[2] != "1.0")
                fail("header: the second line must be \"format ascii|binary_little_endian|binary_big_endian "
                     "1.0\"",
                     line);
            format = t[1];
            ascii_format = format == "ascii";
        } else if (t.empty()) {
            fail("header: empty line", line);
        } else if (t[0] == "comment" || t[0] == "obj_info") {
        } else if (t[0] == "end_header" && t.size() == 1) {
            body = pos;
        } else if (t[0] == "element") {
            if (!elements.empty() && elements.back().name == "face") faces_seen = true;
            PlyElement e;
            if (t.size() != 3 || !integer(t[2], e.count) || e.count < 0)
                fail("header: bad element line " + show(t.size() > 1 ? t[1] : ""), line);
            e.name = t[1];
            elements.push_back(e);
        } else if (t[0] == "property") {
            if (elements.empty()) fail("header: property before any element", line);
            PlyProperty p;
            bool is_signed = false;
            const std::string& element = elements.back().name;
            if (t.size() == 5 && t[1] == "list") {
                p.count_size = ply_type_size(t[2], p.count_signed);
                if (t[2] != "uchar" && t[2] != "uint8" && t[2] != "uint16" && t[2] != "int")
                    hint = " (OpenMesh reads list lengths of type uchar, uint8, uint16 or int, not " +
                           show(t[2]) + ")";
                p.size = ply_type_size(t[3], is_signed);
                p.real = t[3].find("float") != std::string::npos || t[3].find("double") != std::string::npos;
                if (p.count_size == 0 || p.size == 0 || t[2] == "float" || t[2] == "float32" ||
                    t[2] == "double" || t[2] == "float64")
                    fail("header: bad list property types " + show(t[2] + " " + t[3]), line);
                const bool indices =
                    element == "face" && (t[4] == "vertex_indices" || t[4] == "vertex_index");
                // OpenMesh reads every other list as one value (binary: one item; ASCII: one token) and the
                // rest of the element out of step, or stops: nothing after its faces is read, though.
                if (!indices && !faces_seen)
                    fail("header: list property " + show(element + " " + t[4]) +
                             " cannot be read (OpenMesh reads only the face list vertex_indices)",
                         line);
                if (indices && p.real)
                    fail("header: face vertex indices must be integers, got " + show(t[3]), line);
                // OpenMesh forgets face properties declared before the indices and reads out of step.
                if (indices && !elements.back().properties.empty())
                    fail("header: the face list " + show(t[4]) +
                             " must come first (OpenMesh cannot read face properties before it)",
                         line);
                p.as_int = indices;
            } else if (t.size() == 3) {
                p.size = ply_type_size(t[1], is_signed);
                p.real = t[1].find("float") != std::string::npos || t[1].find("double") != std::string::npos;
                if (p.size == 0) fail("header: unknown property type " + show(t[1]), line);
                if (element == "vertex" && (t[2] == "x" || t[2] == "y" || t[2] == "z") && !p.real)
                    fail("header: vertex coordinates must be float or double (OpenMesh reads no others), "
                         "got " +
                             show(t[1]),
                         line);
                // What OpenMesh's binary reader converts (anything else it reports on std::cerr and reads out
                // of step): normals and texture coordinates from float or double only; colours into
                // integers, from float but not from double.
                const std::string& n = t[2];
                const bool colour = ((element == "vertex" || element == "face") &&
                                     (n == "red" || n == "green" || n == "blue" || n == "alpha")) ||
                                    (element == "vertex" &&
                                     (n == "diffuse_red" || n == "diffuse_green" || n == "diffuse_blue"));
                const bool to_float = element == "vertex" && (n == "nx" || n == "ny" || n == "nz" ||
                                                              n == "u" || n == "v" || n == "s" || n == "t");
                if (!ascii_format && to_float && !p.real)
                    fail("header: vertex property " + show(n) +
                             " must be float or double in a binary PLY (OpenMesh reads no others), got " +
                             show(t[1]),
                         line);
                const bool single = t[1] == "float" || t[1] == "float32";
                if (colour && p.real && !single) {
                    if (!ascii_format)
                        fail("header: colour property " + show(element + " " + n) +
                                 " must be an integer or float type in a binary PLY (OpenMesh cannot read "
                                 "double), got " +
                                 show(t[1]),
                             line);
                    p.as_int = true; // ASCII: read with >> into an int, so written as integers
                }
            } else {
                fail("header: bad property line", line);
            }
            elements.back().properties.push_back(p);
        } else {
            fail("header: unknown keyword " + show(t[0]), line);
        }
    }
    if (body == std::string::npos) fail("truncated: the header has no end_header line");
    long long faces = -1;
    for (auto& e : elements) {
        if (e.name == "face") faces = e.count;
        // Every element then takes at least one byte or token, so the walk below ends with the file.
        if (e.properties.empty() && e.count > 0)
            fail("header: element " + show(e.name) + " has " + std::to_string(e.count) +
                 " entries but no properties");
    }
    const bool ascii = format == "ascii", big = format == "binary_big_endian";
    if (!ascii && !big && format != "binary_little_endian")
        fail("header: format must be ascii, binary_little_endian or binary_big_endian, got " + show(format));

    // Walk the body element by element so that every declared count is backed by bytes (or tokens).
    const size_t size = bytes.size();
    auto truncated = [&](const PlyElement& e, long long i) {
        fail("truncated: the header declares " + std::to_string(e.count) + " " + e.name +
             " elements but the file ends inside " + e.name + " " + std::to_string(i));
    };
    if (ascii) {
        std::istringstream in(bytes.substr(body));
        std::string token;
        for (const auto& e : elements)
            for (long long i = 0; i < e.count; ++i)
                for (const auto& p : e.properties) {
                    long long items = 1;
                    if (p.count_size) {
                        if (!(in >> token)) truncated(e, i);
                        if (!integer(token, items) || items < 0)
                            fail(e.name + " " + std::to_string(i) + ": list length " + show(token) +
                                 " is not a count");
                        // Each item takes at least 2 bytes: no list can be longer than the file.
                        if (double(items) * 2 > double(size)) truncated(e, i);
                    }
                    // Every token must be exactly one value of its type, or OpenMesh's reader (`>>` per type)
                    // would split or skip it and read the rest of the file out of step.
                    long long whole = 0;
                    const bool real = p.real && !p.as_int;
                    for (long long k = 0; k < items; ++k) {
                        if (!(in >> token)) truncated(e, i);
                        if (real ? !finite_float(token) : !integer(token, whole))
                            fail(e.name + " " + std::to_string(i) + ": " + show(token) + " is not " +
                                 (real ? "a finite number" : "an integer"));
                    }
                }
    } else {
        const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
        size_t pos = body;
        for (const auto& e : elements) {
            if (e.count == 0) continue;
            // Rows of fixed size (no lists: vertices, most other elements) are skipped in one step.
            size_t row = 0;
            bool fixed = true;
            for (const auto& p : e.properties) row += size_t(p.size), fixed = fixed && p.count_size == 0;
            if (fixed) {
                const size_t rows_there = (size - pos) / row;
                if (rows_there < std::uint64_t(e.count)) truncated(e, (long long)rows_there);
                pos += size_t(e.count) * row;
                continue;
            }
            // The usual face element, one list with a one-byte length per row: a tight loop.
            if (e.properties.size() == 1 && e.properties[0].count_size == 1) {
                const size_t item = size_t(e.properties[0].size);
                for (long long i = 0; i < e.count; ++i) {
                    if (pos >= size) truncated(e, i);
                    const size_t items = data[pos];
                    if (e.properties[0].count_signed && items > 127)
                        fail(e.name + " " + std::to_string(i) + ": negative list length");
                    if ((size - pos - 1) / item < items) truncated(e, i);
                    pos += 1 + items * item;
                }
                continue;
            }
            for (long long i = 0; i < e.count; ++i)
                for (const auto& p : e.properties) {
                    if (p.count_size) {
                        if (size - pos < size_t(p.count_size)) truncated(e, i);
                        const long long items = ply_read_count(data + pos, p.count_size, p.count_signed, big);
                        pos += size_t(p.count_size);
                        if (items < 0) fail(e.name + " " + std::to_string(i) + ": negative list length");
                        if (double(size - pos) < double(items) * p.size) truncated(e, i);
                        pos += size_t(items) * size_t(p.size);
                    } else {
                        if (size - pos < size_t(p.size)) truncated(e, i);
                        pos += size_t(p.size);
                    }
                }
        }
    }
    return {faces, hint, true};
}

TriMesh read_ply(const MeshFile& file) {
    return read_with_openmesh(file, ".ply", check_ply(file.bytes));
}

} // namespace sonarsim::mesh_io

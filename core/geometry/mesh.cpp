#include "core/geometry/mesh.hpp"

#include "core/base/errors.hpp"
#include "core/geometry/mesh_cache.hpp"
#include "core/base/pose.hpp"

#include <OpenMesh/Core/IO/IOManager.hh>
#include <OpenMesh/Core/IO/importer/BaseImporter.hh>
#include <OpenMesh/Core/System/omstream.hh>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <mutex>
#include <set>
#include <sstream>
#include <streambuf>

namespace sonarsim {
namespace {

// OpenMesh accepts much that is broken: it reads a binary STL with a lying triangle count as ASCII and
// returns no faces, skips OBJ vertex lines it cannot read ("v nan 0 0"), drops faces with out-of-range
// indices, allocates whatever a PLY or OFF header or face valence claims (a 2e9-corner OFF face takes
// gigabytes and minutes), loops forever on some malformed PLY headers, and reads some PLY properties out of
// step (printing to std::cerr directly). So OBJ, PLY and STL files get a structural check first (counts
// against the bytes that are really there, every index in range, every coordinate a finite float, only
// property types OpenMesh converts), then OpenMesh parses them into a flat triangle array whose importer
// watches for faces it would drop; its log streams are routed to the load, never to the terminal. OFF files
// are read here. Nothing is "repaired": a file either loads as written or is rejected. Faces with fewer than
// 3 distinct corners have no area and are skipped (OpenMesh does the same); a face that repeats a corner of
// a larger polygon is an error.

/// A failed check: the message (and the 1-based line in text formats, 0 when unknown).
struct Problem {
    std::string message;
    long line = 0;
};

[[noreturn]] void fail(const std::string& message, long line = 0) {
    throw Problem{message, line};
}

std::string lower_extension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

/// A token from the file for a message: quoted, shortened, bytes outside printable ASCII escaped.
std::string show(const std::string& token) {
    std::string s = "\"";
    for (size_t i = 0; i < token.size() && i < 60; ++i) {
        const auto c = static_cast<unsigned char>(token[i]);
        if (c >= 0x20 && c < 0x7f) {
            s += token[i];
        } else {
            char hex[8];
            std::snprintf(hex, sizeof hex, "\\x%02x", unsigned(c));
            s += hex;
        }
    }
    return s + (token.size() > 60 ? "...\"" : "\"");
}

/// A finite single-precision number in decimal notation, written as the whole token (no hex, inf or nan:
/// OpenMesh's readers would read "0x10" as 0 and carry on).
bool finite_float(const std::string& token) {
    if (token.empty() || token.find_first_not_of("0123456789+-.eE") != std::string::npos) return false;
    char* end = nullptr;
    errno = 0;
    const float x = std::strtof(token.c_str(), &end);
    return end == token.c_str() + token.size() && errno != ERANGE && std::isfinite(x);
}

/// A decimal integer written as the whole token.
bool integer(const std::string& token, long long& value) {
    if (token.empty()) return false;
    char* end = nullptr;
    errno = 0;
    value = std::strtoll(token.c_str(), &end, 10);
    return end == token.c_str() + token.size() && errno != ERANGE;
}

/// Lines of a text file split into whitespace-separated tokens; `#` comments removed when asked.
class TextLines {
  public:
    TextLines(const std::string& text, bool hash_comments) : text_(text), comments_(hash_comments) {}
    /// Next line with at least one token; false at the end.
    bool next(std::vector<std::string>& tokens) {
        while (pos_ < text_.size()) {
            size_t end = text_.find('\n', pos_);
            if (end == std::string::npos) end = text_.size();
            std::string line = text_.substr(pos_, end - pos_);
            pos_ = end + 1;
            ++line_;
            if (comments_) line = line.substr(0, line.find('#'));
            tokens.clear();
            std::istringstream in(line);
            for (std::string t; in >> t;) tokens.push_back(t);
            if (!tokens.empty()) return true;
        }
        return false;
    }
    long line() const { return line_; }

  private:
    const std::string& text_;
    bool comments_;
    size_t pos_ = 0;
    long line_ = 0;
};

bool text_like(const std::string& bytes) {
    for (unsigned char c : bytes)
        if (c == 0 || (c < 0x20 && c != '\n' && c != '\r' && c != '\t' && c != '\f' && c != '\v'))
            return false;
    return true;
}

/// What a check learnt: the faces the file declares (OpenMesh must see as many).
struct Expect {
    long long faces = -1;   ///< faces with at least 3 distinct corners (-1: not known)
    std::string hint;       ///< added when OpenMesh refuses the file
    bool all_faces = false; ///< `faces` counts every face, zero-area ones included
};

// ---- OBJ ----

/// An OBJ index ("3", "-1") into `count` elements defined so far, as 1-based; 0 when out of range.
long long obj_index(const std::string& token, long long count) {
    long long i = 0;
    if (!integer(token, i)) return -1;
    const long long resolved = i < 0 ? count + i + 1 : i;
    return i == 0 || resolved < 1 || resolved > count ? 0 : resolved;
}

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

// ---- OFF ----
// Read here, not by OpenMesh: its OFF reader takes a face's corner count from wherever its token stream
// happens to be, so a stray byte can make it allocate gigabytes (fuzzing found several). OFF is simple enough
// to read in full: "OFF" (or COFF, NOFF, STOFF...), the counts, one vertex per line (x y z, then colour or
// normal values, ignored), one face per line (k i1 .. ik, then an optional colour, ignored); # starts a
// comment.

TriMesh read_off(const std::string& text) {
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

// ---- PLY ----

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

// ---- STL ----

bool starts_with_solid(const std::string& bytes) {
    const size_t p = bytes.find_first_not_of(" \t\r\n");
    return p != std::string::npos && bytes.compare(p, 5, "solid") == 0;
}

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

// ---- OpenMesh, watched ----

/// Receives every face and vertex a reader hands over and keeps them as a flat triangle array (no half-edge
/// topology: that took most of the load time). Records the faces that OpenMesh would drop without a word.
class FlatImporter : public OpenMesh::IO::BaseImporter {
  public:
    using VertexHandle = OpenMesh::VertexHandle;
    using FaceHandle = OpenMesh::FaceHandle;
    using HalfedgeHandle = OpenMesh::HalfedgeHandle;
    using EdgeHandle = OpenMesh::EdgeHandle;
    using Status = OpenMesh::Attributes::StatusInfo;

    explicit FlatImporter(std::uintmax_t file_bytes) : file_bytes_(file_bytes) {}

    VertexHandle add_vertex(const OpenMesh::Vec3f& p) override {
        mesh.vertices.emplace_back(p[0], p[1], p[2]);
        return VertexHandle(int(mesh.vertices.size() - 1));
    }
    VertexHandle add_vertex() override { return add_vertex(OpenMesh::Vec3f(0, 0, 0)); }
    void set_point(VertexHandle vh, const OpenMesh::Vec3f& p) override {
        if (vh.idx() >= 0 && size_t(vh.idx()) < mesh.vertices.size())
            mesh.vertices[size_t(vh.idx())] = glm::vec3(p[0], p[1], p[2]);
    }

    FaceHandle add_face(const VHandles& corners) override {
        ++faces_seen;
        const size_t n_vertices = mesh.vertices.size();
        for (const auto& vh : corners)
            if (vh.idx() < 0 || size_t(vh.idx()) >= n_vertices) {
                if (problem.empty())
                    problem = "face " + std::to_string(faces_seen - 1) + " refers to vertex " +
                              std::to_string(vh.idx()) + "; allowed: 0 to " + std::to_string(n_vertices - 1) +
                              " (" + std::to_string(n_vertices) + " vertices)";
                return FaceHandle();
            }
        const size_t distinct = distinct_corners(corners);
        if (distinct < 3) return FaceHandle(); // a point or a line: no area, no echo
        ++faces_with_area;
        if (distinct != corners.size()) {
            if (problem.empty()) problem = "face " + std::to_string(faces_seen - 1) + " repeats a vertex";
            return FaceHandle();
        }
        for (size_t k = 1; k + 1 < corners.size(); ++k) // a fan, as polygons were always split
            mesh.triangles.emplace_back(unsigned(corners[0].idx()), unsigned(corners[k].idx()),
                                        unsigned(corners[k + 1].idx()));
        return FaceHandle(int(faces_with_area - 1));
    }

    /// Readers reserve what the header claims; never more than the file could hold.
    void reserve(unsigned int nv, unsigned int, unsigned int nf) override {
        if (nv <= file_bytes_ && nf <= file_bytes_) mesh.vertices.reserve(nv), mesh.triangles.reserve(nf);
    }
    size_t n_vertices() const override { return mesh.vertices.size(); }
    size_t n_faces() const override { return size_t(faces_with_area); }
    size_t n_edges() const override { return 0; }

    // Attributes, texture data and explicit topology: not needed for tracing.
    HalfedgeHandle add_edge(VertexHandle, VertexHandle) override { return HalfedgeHandle(); }
    FaceHandle add_face(HalfedgeHandle) override { return FaceHandle(); }
    void add_face_texcoords(FaceHandle, VertexHandle, const std::vector<OpenMesh::Vec2f>&) override {}
    void add_face_texcoords(FaceHandle, VertexHandle, const std::vector<OpenMesh::Vec3f>&) override {}
    void set_face_texindex(FaceHandle, int) override {}
    void set_halfedge(VertexHandle, HalfedgeHandle) override {}
    void set_normal(VertexHandle, const OpenMesh::Vec3f&) override {}
    void set_normal(VertexHandle, const OpenMesh::Vec3d&) override {}
    void set_color(VertexHandle, const OpenMesh::Vec3uc&) override {}
    void set_color(VertexHandle, const OpenMesh::Vec4uc&) override {}
    void set_color(VertexHandle, const OpenMesh::Vec3f&) override {}
    void set_color(VertexHandle, const OpenMesh::Vec4f&) override {}
    void set_texcoord(VertexHandle, const OpenMesh::Vec2f&) override {}
    void set_status(VertexHandle, const Status&) override {}
    void set_next(HalfedgeHandle, HalfedgeHandle) override {}
    void set_face(HalfedgeHandle, FaceHandle) override {}
    void request_face_texcoords2D() override {}
    void set_texcoord(HalfedgeHandle, const OpenMesh::Vec2f&) override {}
    void set_texcoord(VertexHandle, const OpenMesh::Vec3f&) override {}
    void set_texcoord(HalfedgeHandle, const OpenMesh::Vec3f&) override {}
    void set_status(HalfedgeHandle, const Status&) override {}
    void set_color(EdgeHandle, const OpenMesh::Vec3uc&) override {}
    void set_color(EdgeHandle, const OpenMesh::Vec4uc&) override {}
    void set_color(EdgeHandle, const OpenMesh::Vec3f&) override {}
    void set_color(EdgeHandle, const OpenMesh::Vec4f&) override {}
    void set_status(EdgeHandle, const Status&) override {}
    void set_normal(FaceHandle, const OpenMesh::Vec3f&) override {}
    void set_normal(FaceHandle, const OpenMesh::Vec3d&) override {}
    void set_color(FaceHandle, const OpenMesh::Vec3uc&) override {}
    void set_color(FaceHandle, const OpenMesh::Vec4uc&) override {}
    void set_color(FaceHandle, const OpenMesh::Vec3f&) override {}
    void set_color(FaceHandle, const OpenMesh::Vec4f&) override {}
    void set_status(FaceHandle, const Status&) override {}
    void add_texture_information(int, std::string) override {}

    TriMesh mesh;
    long long faces_seen = 0, faces_with_area = 0;
    std::string problem;

  private:
    static size_t distinct_corners(const VHandles& c) {
        if (c.size() <= 8) { // the usual triangles and quads: no allocation
            size_t n = 0;
            for (size_t i = 0; i < c.size(); ++i)
                n += size_t(std::find(c.begin(), c.begin() + long(i), c[i]) == c.begin() + long(i));
            return n;
        }
        std::vector<int> idx;
        for (const auto& vh : c) idx.push_back(vh.idx());
        std::sort(idx.begin(), idx.end());
        return size_t(std::unique(idx.begin(), idx.end()) - idx.begin());
    }
    std::uintmax_t file_bytes_;
};

/// Where OpenMesh's own log streams (omerr, omlog, omout: process-wide, by default copied to std::cerr,
/// std::clog and std::cout) now write: the text of the load running on the writing thread, never the
/// terminal. Installed once as those streams' buffer; std::cerr and std::cout, which other threads may be
/// writing to, are never touched. (Not through mostream::connect/disconnect: disconnect leaks the old
/// target, which LeakSanitizer reports.)
class OpenMeshLog : public std::streambuf {
  public:
    /// Sends omerr(), omlog() and omout() here, once per process (never undone).
    static void install() {
        static std::once_flag once;
        std::call_once(once, [] {
            static OpenMeshLog* const log = new OpenMeshLog; // outlives OpenMesh's static streams
            omerr().rdbuf(log), omlog().rdbuf(log), omout().rdbuf(log);
        });
    }

    /// Collects what OpenMesh writes on this thread while it lives.
    class Scope {
      public:
        explicit Scope(std::string& text) : old_(capture_) { capture_ = &text; }
        ~Scope() { capture_ = old_; }
        Scope(const Scope&) = delete;
        Scope& operator=(const Scope&) = delete;

      private:
        std::string* old_;
    };

  protected:
    int overflow(int c) override {
        if (capture_ && c != traits_type::eof()) capture_->push_back(char(c));
        return traits_type::not_eof(c);
    }
    std::streamsize xsputn(const char* s, std::streamsize n) override {
        if (capture_) capture_->append(s, size_t(n));
        return n;
    }

  private:
    static thread_local std::string* capture_;
};
thread_local std::string* OpenMeshLog::capture_ = nullptr;

/// The last non-empty line of `text` (what OpenMesh said last before it gave up).
std::string last_line(const std::string& text) {
    const size_t end = text.find_last_not_of("\r\n");
    if (end == std::string::npos) return "";
    const size_t nl = text.rfind('\n', end), begin = nl == std::string::npos ? 0 : nl + 1;
    return text.substr(begin, end + 1 - begin);
}

/// A read-only stream over bytes in memory (seekable: OpenMesh's PLY reader seeks back after the header).
class MemoryBuffer : public std::streambuf {
  public:
    explicit MemoryBuffer(const std::string& bytes) {
        char* p = const_cast<char*>(bytes.data()); // never written: no put area, no putback
        setg(p, p, p + bytes.size());
    }

  protected:
    pos_type seekoff(off_type off, std::ios_base::seekdir dir, std::ios_base::openmode) override {
        const off_type size = egptr() - eback();
        const off_type pos = dir == std::ios_base::beg   ? off
                             : dir == std::ios_base::cur ? gptr() - eback() + off
                                                         : size + off;
        if (pos < 0 || pos > size) return pos_type(off_type(-1));
        setg(eback(), eback() + pos, egptr());
        return pos_type(pos);
    }
    pos_type seekpos(pos_type pos, std::ios_base::openmode mode) override {
        return seekoff(off_type(pos), std::ios_base::beg, mode);
    }
};

/// The whole file (fopen/fread: istreambuf_iterator takes ~10x longer on large files).
std::string read_all(const std::string& path, std::uintmax_t size_hint) {
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!f) fail(std::string("cannot be read: ") + std::strerror(errno));
    std::string bytes(size_t(size_hint), '\0');
    size_t got = std::fread(bytes.data(), 1, bytes.size(), f.get());
    bytes.resize(got);
    char chunk[65536]; // the file may have grown since its size was taken
    while ((got = std::fread(chunk, 1, sizeof chunk, f.get())) > 0) bytes.append(chunk, got);
    if (std::ferror(f.get())) fail("read error");
    return bytes;
}

/// OBJ, PLY and STL through OpenMesh, after the structural check of the bytes.
TriMesh read_with_openmesh(const std::string& path, const std::string& bytes, const std::string& ext,
                           std::uintmax_t file_bytes) {
    const Expect expect = ext == ".obj"   ? check_obj(bytes)
                          : ext == ".ply" ? check_ply(bytes)
                                          : check_stl(bytes);
    FlatImporter importer(file_bytes);
    std::string said; // what OpenMesh wrote to its log streams
    bool ok = false;
    {
        // OpenMesh's readers are process-wide singletons that keep the file being read in members (the PLY
        // reader: its elements, counts and options; the OBJ reader: materials and path), and the PLY reader
        // switches omerr() off and on: one read at a time. The checks above and below run in parallel.
        static std::mutex mutex;
        const std::lock_guard<std::mutex> lock(mutex);
        OpenMeshLog::install();
        const OpenMeshLog::Scope capture(said);
        OpenMesh::IO::Options opt;
        if (ext == ".ply") { // from the bytes already read: ~20% faster than OpenMesh's own file stream
            MemoryBuffer buffer(bytes);
            std::istream in(&buffer);
            ok = OpenMesh::IO::IOManager().read(in, ext, importer, opt);
        } else { // by name: OBJ material files are found next to it, STL is told binary from ASCII
            ok = OpenMesh::IO::IOManager().read(path, importer, opt);
        }
    }
    // OpenMesh also logs harmless things (skipped zero-area faces, unknown PLY elements): its last words
    // explain a failure but decide nothing. Everything it would misread is caught by the checks.
    if (!ok)
        fail("not a valid " + ext.substr(1) + " mesh" +
             (!expect.hint.empty() || said.empty() ? expect.hint
                                                   : " (OpenMesh: " + show(last_line(said)) + ")"));
    if (!importer.problem.empty()) fail(importer.problem);
    const long long read = expect.all_faces ? importer.faces_seen : importer.faces_with_area;
    if (expect.faces >= 0 && read != expect.faces)
        fail("the file has " + std::to_string(expect.faces) + " faces but OpenMesh read " +
             std::to_string(read));
    return std::move(importer.mesh);
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
    if (!std::ifstream(path).good())
        throw InputError(scene_file, key, where + ": cannot be read: " + std::strerror(errno));
    const std::uintmax_t file_bytes = std::filesystem::file_size(path, ec);
    if (file_bytes == 0) throw InputError(scene_file, key, where + ": file is empty");

    TriMesh out;
    try {
        const std::string bytes = read_all(path, file_bytes);
        out = ext == ".off" ? read_off(bytes) : read_with_openmesh(path, bytes, ext, file_bytes);
    } catch (const Problem& p) {
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

TriMesh object_world_mesh(const ObjectDesc& o, const std::string& scene_file, const std::string& key) {
    const std::shared_ptr<const TriMesh> local =
        o.box_m ? std::make_shared<const TriMesh>(make_box(*o.box_m))
                : cached_mesh(o.mesh_resolved, scene_file, key + ".mesh");
    return transformed_mesh(*local, object_transform(o), scene_file, key);
}

bool mesh_bounds(const TriMesh& m, glm::vec3& lo, glm::vec3& hi) {
    if (m.vertices.empty()) return false;
    lo = hi = m.vertices[0];
    for (auto& v : m.vertices) lo = glm::min(lo, v), hi = glm::max(hi, v);
    return true;
}

} // namespace sonarsim

#include "core/meshfile/mesh_readers.hpp"

#include "core/meshfile/mesh_tokens.hpp"

#include <OpenMesh/Core/IO/IOManager.hh>
#include <OpenMesh/Core/IO/importer/BaseImporter.hh>
#include <OpenMesh/Core/System/omstream.hh>
#include <algorithm>
#include <cstdint>
#include <mutex>
#include <streambuf>
#include <vector>

namespace sonarsim::mesh_io {
namespace {

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

} // namespace

TriMesh read_with_openmesh(const MeshFile& file, const std::string& ext, const Expect& expect) {
    const std::string &path = file.path, &bytes = file.bytes;
    FlatImporter importer(bytes.size());
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

} // namespace sonarsim::mesh_io

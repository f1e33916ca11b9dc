// The whole-file reader (core/base/file_io) and the mesh format table (core/meshfile/mesh_formats).
#include "support.hpp"

#include "core/base/errors.hpp"
#include "core/base/file_io.hpp"
#include "core/geometry/mesh.hpp"
#include "core/meshfile/mesh_formats.hpp"

#include <catch2/catch.hpp>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>

using namespace sonarsim;
namespace fs = std::filesystem;

namespace {

std::string write_file(const std::string& name, const std::string& bytes) {
    const std::string path = test::out_path(name);
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
}

} // namespace

TEST_CASE("read_file_bytes returns every byte, NULs included, up to its limit", "[file_io]") {
    std::string bytes = "solid\0x\r\n";
    bytes += std::string(200000, '\x7f'); // larger than one read chunk
    bytes[3] = '\0';
    const std::string path = write_file("file_io_bytes.bin", bytes);
    CHECK(read_file_bytes(path) == bytes);
    CHECK(read_file_bytes(path, bytes.size()) == bytes);
    CHECK(try_read_file_bytes(path).value() == bytes);
    CHECK_THROWS_WITH(read_file_bytes(path, 1000), path + ": file is more than 1000 bytes");
    CHECK_FALSE(try_read_file_bytes(path, bytes.size() - 1));
    CHECK(read_file_bytes(write_file("file_io_empty.bin", "")).empty());
}

TEST_CASE("read_file_bytes reports in the project's error style", "[file_io]") {
    const std::string missing = test::out_path("file_io_no_such_file");
    fs::remove(missing);
    CHECK_THROWS_WITH(read_file_bytes(missing), missing + ": cannot be read: No such file or directory");
    CHECK_THROWS_WITH(
        read_file_bytes(missing, kAnyFileSize, {"scene.json", "objects[0].mesh", "mesh \"m\": ", ""}),
        "scene.json: objects[0].mesh: mesh \"m\": cannot be read: No such file or directory");
    CHECK_THROWS_WITH(read_file_bytes(missing, kAnyFileSize, {"", "", "", "trajectory file cannot be read"}),
                      missing + ": trajectory file cannot be read");
    CHECK_THROWS_AS(read_file_bytes(missing), InputError);
    CHECK_FALSE(try_read_file_bytes(missing));
    // A directory opens but cannot be read.
    CHECK_THROWS_WITH(read_file_bytes(test::out_path("")), Catch::Contains("read error"));
}

TEST_CASE("the mesh format table: unique lower-case extensions, found in any case", "[mesh][formats]") {
    std::set<std::string> seen;
    for (const MeshFormat& f : mesh_formats()) {
        const std::string ext = f.extension;
        INFO(ext);
        CHECK(ext.size() >= 2);
        CHECK(ext[0] == '.');
        for (const char c : ext) CHECK(c == std::tolower(static_cast<unsigned char>(c)));
        CHECK(seen.insert(ext).second);
        CHECK(f.read != nullptr);
        CHECK(std::string(f.name).size() > 0);
        CHECK(find_mesh_format("dir.v2/model" + ext) == &f);
    }
    CHECK(mesh_extensions() == std::vector<std::string>{".obj", ".ply", ".stl", ".off"}); // table order
    CHECK(mesh_extensions_text() == ".obj, .ply, .stl, .off");
    CHECK(mesh_extensions_text(" ") == ".obj .ply .stl .off");
    CHECK(find_mesh_format("A/B.OBJ") == &mesh_formats()[0]);
    CHECK(find_mesh_format("a/b.Ply") == &mesh_formats()[1]);
    CHECK(find_mesh_format("mesh.json") == nullptr);
    CHECK(find_mesh_format("mesh") == nullptr);
    CHECK(mesh_extension_of("x/Y.StL") == ".stl");
    CHECK_THROWS_WITH(
        load_mesh("m.dae", "s.json", "objects[0].mesh"),
        "s.json: objects[0].mesh: mesh \"m.dae\": unknown extension \".dae\"; allowed: .obj, .ply, "
        ".stl, .off");
}

TEST_CASE("every format of the table loads the same triangle", "[mesh][formats]") {
    const std::map<std::string, std::string> files = {
        {".obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"},
        {".ply",
         "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float "
         "z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 "
         "0 1 2\n"},
        {".stl",
         "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\n"
         "endfacet\nendsolid t\n"},
        {".off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"},
    };
    REQUIRE(files.size() == mesh_formats().size());
    for (const MeshFormat& f : mesh_formats()) {
        INFO(f.extension);
        REQUIRE(files.count(f.extension));
        const std::string path =
            write_file(std::string("formats_triangle") + f.extension, files.at(f.extension));
        const TriMesh m = load_mesh(path, "s.json", "objects[0].mesh");
        REQUIRE(m.vertices.size() == 3);
        REQUIRE(m.triangles.size() == 1);
        CHECK(m.vertices[m.triangles[0][1]] == glm::vec3(1, 0, 0));
        CHECK(m.vertices[m.triangles[0][2]] == glm::vec3(0, 1, 0));
    }
}

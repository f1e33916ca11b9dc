// The process-wide mesh cache (one read per file, rewritten files read again, a byte budget, concurrent
// requests) and mesh loading while another thread writes std::cerr.
#include "support.hpp"

#include "core/base/errors.hpp"
#include "core/geometry/mesh.hpp"
#include "core/geometry/mesh_cache.hpp"

#include <atomic>
#include <catch2/catch.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <future>
#include <iostream>
#include <streambuf>
#include <string>
#include <thread>
#include <vector>

using namespace sonarsim;
namespace fs = std::filesystem;

namespace {

/// Binary little-endian PLY of an n x n grid of unit squares at height z, two triangles each.
void write_grid_ply(const std::string& path, int n, float z) {
    FILE* f = std::fopen(path.c_str(), "wb");
    REQUIRE(f);
    std::fprintf(
        f,
        "ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\nproperty float y\n"
        "property float z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n",
        (n + 1) * (n + 1), 2 * n * n);
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            const float v[3] = {float(i), float(j), z};
            std::fwrite(v, sizeof v, 1, f);
        }
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const int a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
            const unsigned char three = 3;
            const int t1[3] = {a, b, c}, t2[3] = {a, c, d};
            std::fwrite(&three, 1, 1, f), std::fwrite(t1, sizeof t1, 1, f);
            std::fwrite(&three, 1, 1, f), std::fwrite(t2, sizeof t2, 1, f);
        }
    std::fclose(f);
}

/// Moves the file's modification time by `seconds` (a rewrite within one clock tick keeps the old time).
void touch(const std::string& path, int seconds) {
    fs::last_write_time(path, fs::last_write_time(path) + std::chrono::seconds(seconds));
}

/// Swallows what is written to it (std::cerr's stand-in while a thread floods it).
class NullBuffer : public std::streambuf {
  protected:
    int overflow(int c) override { return c; }
    std::streamsize xsputn(const char*, std::streamsize n) override { return n; }
};

} // namespace

TEST_CASE("the mesh cache reads a file once and hands out the same mesh", "[mesh][cache]") {
    MeshCache cache;
    const std::string path = test::out_path("cache_grid.ply");
    write_grid_ply(path, 4, 0);
    const auto a = cache.get(path, "s.json", "objects[0].mesh");
    REQUIRE(a->triangles.size() == 32);
    const auto b = cache.get(path, "other.json", "objects[3].mesh");
    CHECK(a.get() == b.get());
    // Another spelling of the same file.
    const std::string spelled = (fs::path(path).parent_path() / "." / fs::path(path).filename()).string();
    CHECK(cache.get(spelled, "s.json", "k").get() == a.get());
    CHECK(cache.files_read() == 1);
    CHECK(cache.size() == 1);
    CHECK(cache.bytes() == mesh_bytes(*a));
    CHECK(cache.budget_bytes() == MeshCache::kDefaultBudgetBytes);
}

TEST_CASE("a rewritten mesh file is read again", "[mesh][cache]") {
    MeshCache cache;
    const std::string path = test::out_path("cache_rewritten.ply");
    write_grid_ply(path, 4, 0);
    const auto a = cache.get(path, "s.json", "k");
    write_grid_ply(path, 5, 0); // new size
    touch(path, 10);
    const auto b = cache.get(path, "s.json", "k");
    CHECK(b.get() != a.get());
    CHECK(b->triangles.size() == 50);
    CHECK(a->triangles.size() == 32); // a holder keeps what it has
    write_grid_ply(path, 5, 2);       // same size, new contents
    touch(path, 20);
    const auto c = cache.get(path, "s.json", "k");
    CHECK(c.get() != b.get());
    CHECK(c->vertices[0].z == 2.0f);
    CHECK(cache.files_read() == 3);
    CHECK(cache.get(path, "s.json", "k").get() == c.get());
}

TEST_CASE("the mesh cache keeps to its byte budget, least recently used out first", "[mesh][cache]") {
    const std::string p1 = test::out_path("cache_budget_1.ply"), p2 = test::out_path("cache_budget_2.ply"),
                      p3 = test::out_path("cache_budget_3.ply");
    write_grid_ply(p1, 8, 0), write_grid_ply(p2, 8, 1), write_grid_ply(p3, 8, 2);
    const size_t one = mesh_bytes(*MeshCache().get(p1, "s", "k"));
    MeshCache cache(2 * one + one / 2); // room for two
    const auto m1 = cache.get(p1, "s", "k");
    cache.get(p2, "s", "k");
    cache.get(p1, "s", "k"); // p1 is now the most recent: p2 goes when p3 comes
    cache.get(p3, "s", "k");
    CHECK(cache.size() == 2);
    CHECK(cache.bytes() <= cache.budget_bytes());
    CHECK(cache.files_read() == 3);
    CHECK(cache.get(p1, "s", "k").get() == m1.get());
    CHECK(cache.files_read() == 3);
    cache.get(p2, "s", "k");
    CHECK(cache.files_read() == 4);
    cache.set_budget_bytes(one / 2); // smaller than any mesh: nothing is kept, but meshes are handed out
    CHECK(cache.size() == 0);
    CHECK(cache.bytes() == 0);
    CHECK(cache.get(p3, "s", "k")->triangles.size() == 128);
    CHECK(cache.size() == 0);
}

TEST_CASE("mesh errors are not cached", "[mesh][cache]") {
    MeshCache cache;
    const std::string path = test::out_path("cache_fixed_later.ply");
    {
        std::FILE* f = std::fopen(path.c_str(), "wb");
        REQUIRE(f);
        std::fputs("not a mesh\n", f);
        std::fclose(f);
    }
    try {
        cache.get(path, "s.json", "objects[1].mesh");
        FAIL("a bad mesh was accepted");
    } catch (const InputError& e) {
        CHECK(std::string(e.what()).rfind("s.json: objects[1].mesh: mesh \"" + path + "\": not a PLY file",
                                          0) == 0);
    }
    CHECK(cache.size() == 0);
    write_grid_ply(path, 2, 0);
    touch(path, 10);
    CHECK(cache.get(path, "s.json", "k")->triangles.size() == 8);
    CHECK_THROWS_AS(cache.get(test::out_path("no_such_mesh.ply"), "s.json", "k"), InputError);
}

TEST_CASE("concurrent requests for one mesh read it once", "[mesh][cache]") {
    MeshCache cache;
    const std::string path = test::out_path("cache_concurrent.ply");
    write_grid_ply(path, 250, 0); // 125k triangles: long enough a read for the requests to overlap
    std::promise<void> start;
    std::shared_future<void> go = start.get_future().share();
    std::vector<std::future<std::shared_ptr<const TriMesh>>> got;
    for (int t = 0; t < 4; ++t)
        got.push_back(std::async(std::launch::async, [&, go] {
            go.wait();
            return cache.get(path, "s.json", "k");
        }));
    start.set_value();
    std::vector<std::shared_ptr<const TriMesh>> meshes;
    for (auto& f : got) meshes.push_back(f.get());
    CHECK(cache.files_read() == 1);
    for (const auto& m : meshes) {
        CHECK(m.get() == meshes[0].get());
        CHECK(m->triangles.size() == 125000);
    }
}

// Regression: loading used to swap std::cerr's buffer while OpenMesh read, so a thread writing std::cerr at
// the same time made valid meshes fail ("OpenMesh cannot read it"), or crashed the process.
TEST_CASE("loading meshes while another thread writes std::cerr never rejects a valid mesh", "[mesh]") {
    const std::string ply = test::out_path("cerr_grid.ply"), obj = test::out_path("cerr_quad.obj"),
                      stl = test::out_path("cerr_tri.stl");
    write_grid_ply(ply, 3, 0);
    {
        std::FILE* f = std::fopen(obj.c_str(), "w");
        REQUIRE(f);
        std::fputs("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nf 1 1 2\n", f);
        std::fclose(f);
        f = std::fopen(stl.c_str(), "w");
        REQUIRE(f);
        std::fputs("solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                   "endloop\nendfacet\nendsolid t\n",
                   f);
        std::fclose(f);
    }
    NullBuffer null;
    std::streambuf* const old = std::cerr.rdbuf(&null); // set before the writer starts, restored after
    std::atomic<bool> stop{false};
    std::atomic<long> lines{0};
    std::thread writer([&] {
        while (!stop.load()) {
            std::cerr << "noise from another thread " << lines.load() << '\n';
            ++lines;
        }
    });
    int failures = 0;
    std::string first_error;
    for (int i = 0; i < 150; ++i) {
        try {
            CHECK(load_mesh(ply, "s", "k").triangles.size() == 18);
            CHECK(load_mesh(obj, "s", "k").triangles.size() == 2);
            CHECK(load_mesh(stl, "s", "k").triangles.size() == 1);
        } catch (const std::exception& e) {
            if (failures++ == 0) first_error = e.what();
        }
    }
    stop = true;
    writer.join();
    std::cerr.rdbuf(old);
    INFO(first_error);
    CHECK(failures == 0);
    CHECK(lines.load() > 0);
}

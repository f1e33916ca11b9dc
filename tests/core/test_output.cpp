// The atomic writer: every target is checked before anything is replaced.
#include "support.hpp"

#include "core/io/output.hpp"

#include <catch2/catch.hpp>
#include <filesystem>

using namespace sonarsim;
using namespace sonarsim::test;

namespace {

std::string fresh_dir(const std::string& name) {
    const std::string dir = out_path(name);
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

size_t entries(const std::string& dir) {
    size_t n = 0;
    for ([[maybe_unused]] auto& e : std::filesystem::directory_iterator(dir)) ++n;
    return n;
}

} // namespace

TEST_CASE("a target that is a directory fails the write before any file is replaced", "[output]") {
    const std::string dir = fresh_dir("atomic_dir_target");
    write_file_bytes(dir + "/img.png", Bytes{1, 2, 3});
    std::filesystem::create_directory(dir + "/img_polar.png");
    const std::vector<std::pair<std::string, Bytes>> files = {
        {dir + "/img.png", Bytes{9, 9}}, {dir + "/img_polar.png", Bytes{7}}, {dir + "/img.npy", Bytes{5}}};
    try {
        write_files_atomically(files);
        FAIL("no error");
    } catch (const std::runtime_error& e) {
        CHECK(std::string(e.what()) == "cannot write " + dir + "/img_polar.png: it is a directory");
    }
    CHECK(read_file_bytes(dir + "/img.png") == Bytes{1, 2, 3}); // not replaced
    CHECK_FALSE(std::filesystem::exists(dir + "/img.npy"));
    CHECK(entries(dir) == 2); // no temporaries left
}

TEST_CASE("a target in a missing directory fails the write before any file is replaced", "[output]") {
    const std::string dir = fresh_dir("atomic_missing_dir");
    write_file_bytes(dir + "/a.png", Bytes{1});
    try {
        write_files_atomically({{dir + "/a.png", Bytes{2}}, {dir + "/no/such/b.png", Bytes{3}}});
        FAIL("no error");
    } catch (const std::runtime_error& e) {
        CHECK(std::string(e.what()).find("directory " + dir + "/no/such does not exist") !=
              std::string::npos);
    }
    CHECK(read_file_bytes(dir + "/a.png") == Bytes{1});
    CHECK(entries(dir) == 1);
}

TEST_CASE("every file of a set is written when all targets are fine", "[output]") {
    const std::string dir = fresh_dir("atomic_ok");
    write_file_bytes(dir + "/a.png", Bytes{1});
    write_files_atomically({{dir + "/a.png", Bytes{2, 3}}, {dir + "/b.npy", Bytes{4}}});
    CHECK(read_file_bytes(dir + "/a.png") == Bytes{2, 3});
    CHECK(read_file_bytes(dir + "/b.npy") == Bytes{4});
    CHECK(entries(dir) == 2);
}

TEST_CASE("the output table names each file of a frame once", "[output]") {
    SceneDesc s;
    CHECK(render_output_paths("d/x", s) ==
          std::vector<std::string>{"d/x.png", "d/x_polar.png", "d/x.npy", "d/x.json"});
    s.sensor.noise = true; // a sensor that is not ideal: its input is written too
    CHECK(render_output_paths("d/x", s).back() == "d/x_ideal.npy");
    CHECK(render_output_paths("d/x", s).size() == render_outputs().size());
    CHECK(render_outputs_text("p").find("p_polar.png (") != std::string::npos);
}

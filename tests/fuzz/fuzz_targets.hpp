// The bodies of the libFuzzer targets, shared with the Catch2 replay test (tests/input) so that every seed
// and every input a fuzzer ever crashed on also runs in the ordinary and the sanitizer builds. A target may
// only ever see InputError; any other exception, a crash, a sanitizer report, a leak, a hang or a broken
// invariant (checked with abort()) is a finding.
#pragma once
#include "core/analysis/compare.hpp"
#include "core/base/errors.hpp"
#include "core/io/aris_read.hpp"
#include "core/geometry/mesh.hpp"
#include "core/scene/params.hpp"
#include "core/scene/scene_io.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

namespace sonarsim::fuzz {

/// An InputError's message must be one line.
inline void check_message(const InputError& e) {
    if (std::string(e.what()).find('\n') != std::string::npos) std::abort();
}

/// Every scene parameter of an accepted scene must be within the table's bounds.
inline void check_scene(const SceneDesc& s) {
    for (const ParamSpec& p : scene_params()) validate_value(p, p.get(s), "check", p.key); // throws if not
    validate_scene(s, "check");
}

/// Scene text: parse_scene, the scene_to_json round trip, and the first line as `--set` and `--pose` text.
inline void scene_input(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        const SceneDesc s = parse_scene(text, "fuzz.json", "/fuzz");
        try {
            check_scene(s);
            const json j = scene_to_json(s);
            const SceneDesc t = parse_scene(j.dump(), "roundtrip.json", "/fuzz");
            if (scene_to_json(t) != j) std::abort(); // an accepted scene must survive its own serialisation
        } catch (const InputError&) {
            std::abort(); // accepted once, rejected on the second look: something was not validated
        }
    } catch (const InputError& e) {
        check_message(e);
    }
    const std::string line = text.substr(0, std::min(text.find('\n'), std::size_t(256)));
    try {
        SceneDesc s = default_scene();
        apply_setting_text(s, line, "--set");
        for (const ParamSpec& p : scene_params()) validate_value(p, p.get(s), "check", p.key);
    } catch (const InputError& e) {
        check_message(e);
    }
    try {
        const Pose p = parse_pose_text(line, "--pose");
        for (double x : p.position_m)
            if (!std::isfinite(x)) std::abort();
    } catch (const InputError& e) {
        check_message(e);
    }
}

/// A private temporary directory for mesh inputs, removed at exit.
class TempDir {
  public:
    TempDir() {
        const char* env = std::getenv("TMPDIR");
        std::string base =
            env && *env ? env : (std::filesystem::is_directory("/dev/shm") ? "/dev/shm" : "/tmp");
        std::string templ = base + "/sonarsim-fuzz-XXXXXX";
        if (!::mkdtemp(templ.data())) std::abort();
        path_ = templ;
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    const std::string& path() const { return path_; }

  private:
    std::string path_;
};

/// Mesh bytes: the first byte picks the format ('0' obj, '1' ply, '2' stl, '3' off; any byte: its value mod
/// 4), the rest is the file. load_mesh must accept it as a valid triangle mesh or throw InputError.
inline void mesh_input(const std::uint8_t* data, std::size_t size) {
    if (size < 1) return;
    static const char* const ext[] = {".obj", ".ply", ".stl", ".off"};
    static TempDir dir;
    const std::string path = dir.path() + "/input" + ext[data[0] % 4];
    {
        std::ofstream f(path, std::ios::binary | std::ios::trunc);
        f.write(reinterpret_cast<const char*>(data + 1), std::streamsize(size - 1));
        if (!f) std::abort();
    }
    try {
        const TriMesh m = load_mesh(path, "fuzz.json", "objects[0].mesh");
        if (m.triangles.empty()) std::abort();
        for (const auto& v : m.vertices)
            if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) std::abort();
        for (const auto& t : m.triangles)
            if (t.x >= m.vertices.size() || t.y >= m.vertices.size() || t.z >= m.vertices.size())
                std::abort();
    } catch (const InputError& e) {
        check_message(e);
    }
}

/// ARIS recording bytes: the frame count, then up to three frames; each accepted frame must have the size its
/// header says and levels in (0, 80] dB or -inf; frame 0's statistics must be computable.
inline void aris_input(const std::uint8_t* data, std::size_t size) {
    const std::vector<std::uint8_t> bytes(data, data + size);
    try {
        const std::size_t n = aris_frame_count(bytes, "fuzz.aris");
        if (n == 0) std::abort();
        for (std::size_t k = 0; k < std::min<std::size_t>(n, 3); ++k) {
            const ArisFrame f = parse_aris_frame(bytes, k, "fuzz.aris");
            if (f.level_db.bins != f.info.samples || f.level_db.beams != f.info.beams ||
                f.level_db.level_db.size() != std::size_t(f.info.samples) * std::size_t(f.info.beams))
                std::abort();
            for (float v : f.level_db.level_db)
                if (!(std::isinf(v) && v < 0) && !(v > 0 && v <= 80)) std::abort();
            if (k == 0) {
                const ImageStats st = image_stats(f.level_db);
                if (!(st.floor_fraction >= 0 && st.floor_fraction <= 1)) std::abort();
            }
        }
    } catch (const InputError& e) {
        check_message(e);
    }
}

} // namespace sonarsim::fuzz

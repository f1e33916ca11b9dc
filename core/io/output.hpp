// The files a render writes, in one table (PNG, .npy float32 L_EN, metadata JSON), and the atomic writer
// (every target checked, then temporaries, then renames).
#pragma once
#include "core/display/image.hpp"
#include "core/io/png.hpp"
#include "core/scene/params.hpp"
#include "core/shading/shade.hpp"

#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace sonarsim {

struct Frame;

/// NumPy .npy v1.0, little-endian float32, C order, shape (bins, beams).
Bytes encode_npy(const PolarImage& image);
/// NumPy .npy v1.0 of `bytes` bytes at `data`, C order: `descr` "<f4" or "<i4", `shape` e.g. {bins, beams,
/// 3}.
Bytes encode_npy_array(const void* data, std::size_t bytes, const std::string& descr,
                       const std::vector<std::size_t>& shape);

/// Checks every target first (its directory exists and is writable, the target is not a directory), then
/// writes every (path, bytes) pair to a temporary file beside its target, then renames them all. On any
/// failure the temporaries are removed and no target is created, truncated or replaced; throws
/// std::runtime_error naming the path.
void write_files_atomically(const std::vector<std::pair<std::string, Bytes>>& files);

/// A file written piece by piece into a temporary beside `path` and renamed onto it by commit(); removed
/// if never committed (an error, an exception). Throws std::runtime_error naming the path.
class AtomicFile {
  public:
    explicit AtomicFile(std::string path);
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;
    void write(const void* data, size_t bytes);
    void write(const Bytes& b) { write(b.data(), b.size()); }
    std::uint64_t size() const { return size_; }
    void commit();

  private:
    std::string path_, tmp_;
    std::FILE* f_ = nullptr;
    std::uint64_t size_ = 0;
};

/// Parses an .npy file as encode_npy writes it (float32 little-endian, C order, 2-D); throws
/// std::runtime_error naming `path` when it is not one.
PolarImage decode_npy(const Bytes& bytes, const std::string& path);
/// The float32 values of an .npy file as encode_npy_array writes it ('<f4', C order), of any shape of
/// `count` values; throws std::runtime_error naming `path` otherwise.
std::vector<float> decode_npy_values(const Bytes& bytes, const std::string& path, std::size_t count);

/// One file of a rendered frame: PREFIX + suffix.
struct RenderOutput {
    const char* suffix; ///< ".png", "_polar.png", ...
    const char* what;   ///< what it holds, for messages and docs
    /// The file's bytes; `metadata_more`: keys the metadata adds (write_render_files), others ignore it.
    Bytes (*encode)(const SceneDesc& scene, const Frame& frame, const json& metadata_more);
    bool (*wanted)(const SceneDesc& scene) = nullptr; ///< written only where it says so (null: always)
    const char* what_ideal =
        nullptr; ///< what it holds under the ideal sensor, where that differs (null: what)
    bool written_for(const SceneDesc& scene) const { return !wanted || wanted(scene); }
    /// What it holds in `scene`'s files (null: in general).
    const char* what_for(const SceneDesc* scene) const;
};

/// The one table of the files a frame is written as: by `render`, the viewer's snapshot and `batch`.
const std::vector<RenderOutput>& render_outputs();

/// PREFIX + each suffix of render_outputs(), in table order.
std::vector<std::string> render_output_paths(const std::string& prefix, const SceneDesc& scene);

/// "PREFIX.png (sector image), PREFIX_polar.png (...), ...": the files, for messages and help texts.
std::string render_outputs_text(const std::string& prefix, const SceneDesc* scene = nullptr);

/// Writes every file of render_outputs() for `prefix`, and the `extra` files (a 3D view PNG, a scene file),
/// in one atomic step; `metadata_more`: keys added to the metadata (about extra files).
void write_render_files(const std::string& prefix, const SceneDesc& scene, const Frame& frame,
                        std::vector<std::pair<std::string, Bytes>> extra = {},
                        const json& metadata_more = nullptr);

Bytes to_bytes(const std::string& text);

} // namespace sonarsim

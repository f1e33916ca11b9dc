// Meshes loaded once per process and shared by every scene and thread: the viewer's UI thread and its render
// worker, and every SceneGeometry built while editing, ask for the same files.
#pragma once
#include "core/geometry/mesh.hpp"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

namespace sonarsim {

/// Meshes in local coordinates (unplaced), keyed by the file's resolved path, size and modification time: a
/// rewritten file is read again. Thread-safe; concurrent requests for one file read it once. The least
/// recently used meshes beyond the byte budget are dropped (whoever holds one keeps it). Errors are not
/// cached: the next request reads the file again and reports with its own scene file and key.
class MeshCache {
  public:
    static constexpr std::size_t kDefaultBudgetBytes = std::size_t(2) << 30; ///< 2 GiB

    explicit MeshCache(std::size_t budget_bytes = kDefaultBudgetBytes);
    ~MeshCache();
    MeshCache(const MeshCache&) = delete;
    MeshCache& operator=(const MeshCache&) = delete;

    /// The process-wide cache (what SceneGeometry uses).
    static MeshCache& global();

    /// The mesh in `path`, loaded by load_mesh (same checks, same InputError(scene_file, key, ...)).
    std::shared_ptr<const TriMesh> get(const std::string& path, const std::string& scene_file,
                                       const std::string& key);

    /// Byte budget; lowering it drops least recently used meshes at once.
    std::size_t budget_bytes() const;
    void set_budget_bytes(std::size_t bytes);
    /// Bytes the cached meshes take (mesh_bytes of each), and how many there are.
    std::size_t bytes() const;
    std::size_t size() const;
    /// Files read so far (successful loads; for tests and benchmarks).
    std::uint64_t files_read() const;
    void clear();

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// MeshCache::global().get(path, scene_file, key).
std::shared_ptr<const TriMesh> cached_mesh(const std::string& path, const std::string& scene_file,
                                           const std::string& key);

/// World-space mesh of one object: its mesh (from the global cache) or box, placed by object_transform.
TriMesh object_world_mesh(const ObjectDesc& object, const std::string& scene_file, const std::string& key);

/// Heap bytes of a mesh's arrays.
std::size_t mesh_bytes(const TriMesh& mesh);

} // namespace sonarsim

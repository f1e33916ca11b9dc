#include "core/geometry/mesh_cache.hpp"

#include <condition_variable>
#include <filesystem>
#include <list>
#include <map>
#include <mutex>
#include <optional>
#include <tuple>

namespace sonarsim {
namespace {

/// What identifies a file's contents without reading it.
struct FileKey {
    std::string path; ///< canonical: symlinks and ".." resolved
    std::uintmax_t size = 0;
    std::int64_t mtime = 0; ///< modification time in the file clock's ticks
    bool operator<(const FileKey& o) const {
        return std::tie(path, size, mtime) < std::tie(o.path, o.size, o.mtime);
    }
    bool operator==(const FileKey& o) const { return !(*this < o) && !(o < *this); }
};

std::optional<FileKey> file_key(const std::string& path) {
    namespace fs = std::filesystem;
    std::error_code ec;
    FileKey k;
    k.path = fs::canonical(path, ec).string();
    if (ec) return std::nullopt;
    k.size = fs::file_size(k.path, ec);
    if (ec) return std::nullopt;
    const auto t = fs::last_write_time(k.path, ec);
    if (ec) return std::nullopt;
    k.mtime = std::int64_t(t.time_since_epoch().count());
    return k;
}

} // namespace

struct MeshCache::Impl {
    struct Entry {
        std::shared_ptr<const TriMesh> mesh; ///< null while a thread loads it
        std::size_t bytes = 0;
        std::list<FileKey>::iterator lru; ///< valid once loaded
    };
    mutable std::mutex mutex;
    std::condition_variable loaded; ///< a load finished (or failed)
    std::map<FileKey, Entry> entries;
    std::list<FileKey> lru; ///< loaded entries, most recently used first
    std::size_t budget = 0, used = 0;
    std::uint64_t reads = 0;

    void drop(std::map<FileKey, Entry>::iterator it) {
        used -= it->second.bytes;
        lru.erase(it->second.lru);
        entries.erase(it);
    }
    void evict() {
        while (used > budget && !lru.empty()) drop(entries.find(lru.back()));
    }
};

MeshCache::MeshCache(std::size_t budget_bytes) : impl_(std::make_unique<Impl>()) {
    impl_->budget = budget_bytes;
}

MeshCache::~MeshCache() = default;

MeshCache& MeshCache::global() {
    static MeshCache cache;
    return cache;
}

std::shared_ptr<const TriMesh> MeshCache::get(const std::string& path, const std::string& scene_file,
                                              const std::string& key) {
    const std::optional<FileKey> k = file_key(path);
    if (!k) { // missing, unreadable...: load_mesh says what is wrong
        auto mesh = std::make_shared<const TriMesh>(load_mesh(path, scene_file, key));
        const std::lock_guard<std::mutex> lock(impl_->mutex);
        ++impl_->reads;
        return mesh;
    }
    Impl& c = *impl_;
    std::unique_lock<std::mutex> lock(c.mutex);
    for (auto it = c.entries.find(*k); it != c.entries.end(); it = c.entries.find(*k)) {
        if (it->second.mesh) {
            c.lru.splice(c.lru.begin(), c.lru, it->second.lru);
            return it->second.mesh;
        }
        c.loaded.wait(lock); // another thread is reading this file; if it fails, read it here
    }
    c.entries.emplace(*k, Impl::Entry{});
    lock.unlock();

    std::shared_ptr<TriMesh> mesh;
    try {
        mesh = std::make_shared<TriMesh>(load_mesh(path, scene_file, key));
        mesh->vertices.shrink_to_fit();
        mesh->triangles.shrink_to_fit();
    } catch (...) {
        lock.lock();
        c.entries.erase(*k);
        c.loaded.notify_all();
        throw;
    }
    const bool unchanged = file_key(path) == k; // rewritten while being read: do not keep it
    lock.lock();
    ++c.reads;
    auto it = c.entries.find(*k);
    if (unchanged) {
        it->second.mesh = mesh;
        it->second.bytes = mesh_bytes(*mesh);
        c.used += it->second.bytes;
        c.lru.push_front(*k);
        it->second.lru = c.lru.begin();
        c.evict(); // a mesh larger than the whole budget is handed out but not kept
    } else {
        c.entries.erase(it);
    }
    c.loaded.notify_all();
    return mesh;
}

std::size_t MeshCache::budget_bytes() const {
    const std::lock_guard<std::mutex> lock(impl_->mutex);
    return impl_->budget;
}

void MeshCache::set_budget_bytes(std::size_t bytes) {
    const std::lock_guard<std::mutex> lock(impl_->mutex);
    impl_->budget = bytes;
    impl_->evict();
}

std::size_t MeshCache::bytes() const {
    const std::lock_guard<std::mutex> lock(impl_->mutex);
    return impl_->used;
}

std::size_t MeshCache::size() const {
    const std::lock_guard<std::mutex> lock(impl_->mutex);
    return impl_->lru.size();
}

std::uint64_t MeshCache::files_read() const {
    const std::lock_guard<std::mutex> lock(impl_->mutex);
    return impl_->reads;
}

void MeshCache::clear() {
    const std::lock_guard<std::mutex> lock(impl_->mutex);
    while (!impl_->lru.empty()) impl_->drop(impl_->entries.find(impl_->lru.back()));
}

std::shared_ptr<const TriMesh> cached_mesh(const std::string& path, const std::string& scene_file,
                                           const std::string& key) {
    return MeshCache::global().get(path, scene_file, key);
}

std::size_t mesh_bytes(const TriMesh& m) {
    return m.vertices.capacity() * sizeof(glm::vec3) + m.triangles.capacity() * sizeof(glm::uvec3);
}

TriMesh object_world_mesh(const ObjectDesc& o, const std::string& scene_file, const std::string& key) {
    const std::shared_ptr<const TriMesh> local =
        o.box_m ? std::make_shared<const TriMesh>(make_box(*o.box_m))
                : cached_mesh(o.mesh_resolved, scene_file, key + ".mesh");
    return transformed_mesh(*local, object_transform(o), scene_file, key);
}

} // namespace sonarsim

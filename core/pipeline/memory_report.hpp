// What the process keeps between images, against its budgets: the meshes cached (MeshCache) and the
// per-frame buffers kept for reuse (scratch pool). `sonarsim render` prints it; the viewer shows it.
#pragma once
#include <cstddef>
#include <string>

namespace sonarsim {

struct MemoryReport {
    std::size_t mesh_bytes = 0, mesh_budget_bytes = 0; ///< MeshCache::global()
    std::size_t kept_bytes = 0, kept_budget_bytes = 0; ///< scratch::kept_bytes(), kScratchPoolMaxBytes
};

/// The process's figures now.
MemoryReport memory_report();

/// Bytes as MiB: a tenth below 10 MiB (a small mesh is not "0"), whole above ("0.4", "30").
std::string mib_text(std::size_t bytes);

/// "meshes 12 of 2048 MiB, kept buffers 30 of 512 MiB".
std::string to_string(const MemoryReport& m);

} // namespace sonarsim

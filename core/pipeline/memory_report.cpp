#include "core/pipeline/memory_report.hpp"

#include "core/base/scratch_pool.hpp"
#include "core/geometry/mesh_cache.hpp"

#include <cstdio>

namespace sonarsim {

MemoryReport memory_report() {
    MemoryReport m;
    const MeshCache& cache = MeshCache::global();
    m.mesh_bytes = cache.bytes(), m.mesh_budget_bytes = cache.budget_bytes();
    m.kept_bytes = scratch::kept_bytes(), m.kept_budget_bytes = scratch::kScratchPoolMaxBytes;
    return m;
}

std::string mib_text(std::size_t bytes) {
    char t[32];
    const double v = double(bytes) / double(1 << 20);
    std::snprintf(t, sizeof t, v < 10 && bytes > 0 ? "%.1f" : "%.0f", v);
    return t;
}

std::string to_string(const MemoryReport& m) {
    const auto mib = mib_text;
    return "meshes " + mib(m.mesh_bytes) + " of " + mib(m.mesh_budget_bytes) + " MiB, kept buffers " +
           mib(m.kept_bytes) + " of " + mib(m.kept_budget_bytes) + " MiB";
}

} // namespace sonarsim

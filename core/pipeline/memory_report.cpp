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

std::string to_string(const MemoryReport& m) {
    const auto mib = [](std::size_t b) { // a tenth below 10 MiB (a small mesh is not "0")
        char t[32];
        const double v = double(b) / double(1 << 20);
        std::snprintf(t, sizeof t, v < 10 && b > 0 ? "%.1f" : "%.0f", v);
        return std::string(t);
    };
    return "meshes " + mib(m.mesh_bytes) + " of " + mib(m.mesh_budget_bytes) + " MiB, kept buffers " +
           mib(m.kept_bytes) + " of " + mib(m.kept_budget_bytes) + " MiB";
}

} // namespace sonarsim

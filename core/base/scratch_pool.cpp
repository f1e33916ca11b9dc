#include "core/base/scratch_pool.hpp"

#include <mutex>

namespace sonarsim::scratch {
namespace {

std::mutex pool_mutex;
std::vector<std::vector<double>> pool; // kept buffers, at their last size

} // namespace

std::vector<double> take(std::size_t n) {
    std::vector<double> v;
    {
        std::lock_guard<std::mutex> lock(pool_mutex);
        // The smallest kept buffer that holds n, else the largest (it grows).
        std::size_t best = pool.size();
        for (std::size_t i = 0; i < pool.size(); ++i) {
            const bool fits = pool[i].size() >= n;
            if (best == pool.size() ||
                (fits && (pool[best].size() < n || pool[i].size() < pool[best].size())) ||
                (!fits && pool[best].size() < n && pool[i].size() > pool[best].size()))
                best = i;
        }
        if (best < pool.size()) {
            v = std::move(pool[best]);
            pool.erase(pool.begin() + std::ptrdiff_t(best));
        }
    }
    v.resize(n);
    return v;
}

void give(std::vector<double>&& v) {
    std::lock_guard<std::mutex> lock(pool_mutex);
    if (int(pool.size()) < kScratchPoolBuffers) pool.push_back(std::move(v));
    v = {};
}

} // namespace sonarsim::scratch

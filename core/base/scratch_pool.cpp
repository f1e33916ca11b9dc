#include "core/base/scratch_pool.hpp"

#include <cstdint>
#include <mutex>

namespace sonarsim::scratch {
namespace {

// Never destroyed: a shared frame may give its buffer back while the process exits (Python's shutdown).
std::mutex& pool_mutex = *new std::mutex;

/// The kept buffers of an element type, at their last size.
template <class T> std::vector<std::vector<T>>& pool() {
    static auto* kept = new std::vector<std::vector<T>>;
    return *kept;
}

/// Bytes of one type's kept buffers (under pool_mutex).
template <class T> std::size_t bytes_of() {
    std::size_t n = 0;
    for (const auto& v : pool<T>()) n += v.capacity() * sizeof(T);
    return n;
}
std::size_t all_bytes() {
    return bytes_of<double>() + bytes_of<float>() + bytes_of<std::uint8_t>();
}

} // namespace

template <class T> std::vector<T> take(std::size_t n) {
    std::vector<T> v;
    {
        std::lock_guard<std::mutex> lock(pool_mutex);
        std::vector<std::vector<T>>& kept = pool<T>();
        // The smallest kept buffer that holds n, else the largest (it grows).
        std::size_t best = kept.size();
        for (std::size_t i = 0; i < kept.size(); ++i) {
            const bool fits = kept[i].size() >= n;
            if (best == kept.size() ||
                (fits && (kept[best].size() < n || kept[i].size() < kept[best].size())) ||
                (!fits && kept[best].size() < n && kept[i].size() > kept[best].size()))
                best = i;
        }
        if (best < kept.size()) {
            v = std::move(kept[best]);
            kept.erase(kept.begin() + std::ptrdiff_t(best));
        }
    }
    v.resize(n);
    return v;
}

template <class T> void give(std::vector<T>&& v) {
    std::lock_guard<std::mutex> lock(pool_mutex);
    if (int(pool<T>().size()) < kScratchPoolBuffers &&
        all_bytes() + v.capacity() * sizeof(T) <= kScratchPoolMaxBytes)
        pool<T>().push_back(std::move(v));
    v = {};
}

std::size_t kept_bytes() {
    std::lock_guard<std::mutex> lock(pool_mutex);
    return all_bytes();
}

template std::vector<double> take<double>(std::size_t);
template std::vector<float> take<float>(std::size_t);
template void give<double>(std::vector<double>&&);
template void give<float>(std::vector<float>&&);
template std::vector<std::uint8_t> take<std::uint8_t>(std::size_t);
template void give<std::uint8_t>(std::vector<std::uint8_t>&&);

} // namespace sonarsim::scratch

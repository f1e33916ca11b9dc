// A per-thread memo of a function whose argument comes in a few values, such as the adaptive sampler's cell
// and column widths (a base width / 3^k): the last few results, keys compared exactly, the oldest replaced.
#pragma once
#include <array>
#include <cstddef>
#include <utility>

namespace sonarsim {

/// make(key), from the calling thread's last N results of this call site (each lambda type has a store of
/// its own, so the key must hold whatever else the result depends on). The reference stays valid until N
/// more keys missed at the same call site on the same thread.
template <std::size_t N, class Key, class Make> const auto& recent_value(const Key& key, Make make) {
    using Value = decltype(make(key));
    struct Entry {
        Key key{};
        Value value{};
        bool used = false;
    };
    thread_local std::array<Entry, N> store{};
    thread_local std::size_t next = 0;
    for (const Entry& e : store)
        if (e.used && e.key == key) return e.value;
    Entry& e = store[next];
    next = (next + 1) % N;
    e.key = key, e.value = make(key), e.used = true;
    return e.value;
}

} // namespace sonarsim

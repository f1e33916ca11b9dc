// Little-endian binary fields for the file writers (ARIS headers, MCAP records, CDR messages).
#pragma once
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

namespace sonarsim::le {

using Bytes = std::vector<std::uint8_t>;

/// Stores `v` (an integer or IEEE float) little-endian at `offset` of `b`, growing it when needed.
template <typename T> void put(Bytes& b, size_t offset, T v) {
    static_assert(std::is_arithmetic_v<T>, "numbers only");
    static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "a little-endian host");
    if (b.size() < offset + sizeof v) b.resize(offset + sizeof v);
    std::memcpy(b.data() + offset, &v, sizeof v);
}

/// Appends `v` little-endian.
template <typename T> void append(Bytes& b, T v) {
    put(b, b.size(), v);
}

/// Appends raw bytes.
inline void append_bytes(Bytes& b, const void* data, size_t n) {
    const auto* p = static_cast<const std::uint8_t*>(data);
    b.insert(b.end(), p, p + n);
}

inline void append_bytes(Bytes& b, const std::string& s) {
    append_bytes(b, s.data(), s.size());
}

} // namespace sonarsim::le

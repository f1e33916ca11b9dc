// OMG CDR, little-endian (ROS 2's XCDR1 plain CDR), as ROS 2 messages are serialised in a bag: a 4-byte
// encapsulation header, then each primitive aligned to its size counted from the end of that header;
// strings and sequences carry a uint32 count.
#pragma once
#include "core/base/le_bytes.hpp"
#include "core/io/output.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace sonarsim {

class Cdr {
  public:
    Cdr() : b_{0x00, 0x01, 0x00, 0x00} {} // CDR_LE, options 0
    template <typename T> void put(T v) {
        align(sizeof v);
        le::append<T>(b_, v);
    }
    void put_string(const std::string& s) {
        put<std::uint32_t>(std::uint32_t(s.size() + 1)); // counts the terminating NUL
        le::append_bytes(b_, s.c_str(), s.size() + 1);
    }
    template <typename T> void put_sequence(const std::vector<T>& v) {
        put<std::uint32_t>(std::uint32_t(v.size()));
        for (T x : v) put<T>(x);
    }
    void put_octets(const Bytes& v) {
        put<std::uint32_t>(std::uint32_t(v.size()));
        b_.insert(b_.end(), v.begin(), v.end());
    }
    Bytes take() { return std::move(b_); }

  private:
    void align(size_t n) {
        while ((b_.size() - 4) % n) b_.push_back(0);
    }
    Bytes b_;
};

} // namespace sonarsim

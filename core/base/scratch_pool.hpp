// Large per-frame buffers kept between frames. A stage that needs tens of megabytes every frame takes them
// here and gives them back when done, so that the next frame writes into memory already mapped: fresh pages
// from the system cost a fault and a clear every 4 KiB (at 30 MB a frame, milliseconds). Thread-safe; keeps
// at most kScratchPoolBuffers buffers of each element type (double, float and std::uint8_t: the fan's
// pixels, given back when the last frame holding them is dropped, see Simulator), and at most
// kScratchPoolMaxBytes over all of them (kept_bytes() reports what it holds).
#pragma once
#include <cstddef>
#include <vector>

namespace sonarsim::scratch {

constexpr int kScratchPoolBuffers = 8;
/// Bytes (capacity) the pool may keep over every element type: a buffer given back beyond it is freed.
constexpr std::size_t kScratchPoolMaxBytes = std::size_t(512) << 20;

/// A vector of n values whose contents are unspecified (a kept buffer shrinks without touching its memory).
template <class T> std::vector<T> take(std::size_t n);

/// Keeps v for a later take (or frees it when the pool holds kScratchPoolBuffers of its type, or keeping it
/// would take the pool past kScratchPoolMaxBytes).
template <class T> void give(std::vector<T>&& v);

/// Bytes the kept buffers hold (their capacity): at most kScratchPoolMaxBytes.
std::size_t kept_bytes();

} // namespace sonarsim::scratch

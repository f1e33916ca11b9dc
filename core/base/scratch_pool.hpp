// Large per-frame buffers kept between frames. A stage that needs tens of megabytes every frame takes them
// here and gives them back when done, so that the next frame writes into memory already mapped: fresh pages
// from the system cost a fault and a clear every 4 KiB (at 30 MB a frame, milliseconds). Thread-safe; keeps
// at most kScratchPoolBuffers buffers of each element type (double, float and std::uint8_t: the fan's
// pixels, given back when the last frame holding them is dropped, see Simulator).
#pragma once
#include <cstddef>
#include <vector>

namespace sonarsim::scratch {

constexpr int kScratchPoolBuffers = 8;

/// A vector of n values whose contents are unspecified (a kept buffer shrinks without touching its memory).
template <class T> std::vector<T> take(std::size_t n);

/// Keeps v for a later take (or frees it when the pool is full).
template <class T> void give(std::vector<T>&& v);

} // namespace sonarsim::scratch

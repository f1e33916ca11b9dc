// Wall-clock timing of pipeline stages.
#pragma once
#include <chrono>

namespace sonarsim {

/// Milliseconds since t0.
inline double ms_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

} // namespace sonarsim

// Sums of intensities carried as natural logarithms, for levels far outside double's range.
#pragma once
#include "core/base/units.hpp"

#include <cmath>
#include <limits>

namespace sonarsim {

/// Log-domain accumulator: value = exp(m) * s.
struct LogSum {
    double m = -std::numeric_limits<double>::infinity(), s = 0;
    void add(double x) {
        if (x == -std::numeric_limits<double>::infinity()) return;
        if (x > m)
            s = s * std::exp(m - x) + 1, m = x;
        else
            s += std::exp(x - m);
    }
    double log_value() const { return s > 0 ? m + std::log(s) : -std::numeric_limits<double>::infinity(); }
};

} // namespace sonarsim

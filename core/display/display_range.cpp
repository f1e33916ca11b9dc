#include "core/display/display_range.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace sonarsim {

namespace {

/// The percentile range of `img`'s finite levels, row k's samples weighted by `row_weight(k)`.
template <class Weight>
DisplayParams percentile_display(const PolarImage& img, const DisplayParams& d, Weight row_weight) {
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    for (float v : img.level_db)
        if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
    if (!(lo <= hi)) return d;
    constexpr int kBins = 4096;
    std::vector<double> hist(kBins, 0.0);
    const double width = std::max(double(hi) - lo, 1e-6) / kBins;
    double total = 0;
    for (int k = 0; k < img.bins; ++k) {
        const double weight = row_weight(k);
        for (int b = 0; b < img.beams; ++b)
            if (const float v = img.level_db[size_t(k) * img.beams + b]; std::isfinite(v)) {
                hist[size_t(std::min(double(kBins - 1), (v - lo) / width))] += weight;
                total += weight;
            }
    }
    auto percentile = [&](double p) {
        const double want = p * total;
        double below = 0;
        for (int i = 0; i < kBins; ++i) {
            if (below + hist[size_t(i)] >= want && hist[size_t(i)] > 0)
                return lo + width * (i + (want - below) / hist[size_t(i)]);
            below += hist[size_t(i)];
        }
        return double(hi);
    };
    DisplayParams out = d;
    out.hi_db = percentile(0.995);
    out.lo_db = std::max(percentile(0.05), out.hi_db - kAutoDisplaySpanDb);
    if (out.hi_db < out.lo_db + 1) {
        const double mid = 0.5 * (out.lo_db + out.hi_db);
        out.lo_db = mid - 0.5, out.hi_db = mid + 0.5;
    }
    return out;
}

} // namespace

DisplayParams effective_display(const PolarImage& img, const DisplayParams& d, const SonarGrid& grid) {
    if (!d.auto_range || img.bins != grid.bins) return d;
    // The fan's area grows with range.
    return percentile_display(img, d, [&](int k) { return grid.bin_centre_m(k); });
}

DisplayParams effective_display(const PolarImage& img, const DisplayParams& d) {
    if (!d.auto_range) return d;
    return percentile_display(img, d, [](int) { return 1.0; });
}

} // namespace sonarsim

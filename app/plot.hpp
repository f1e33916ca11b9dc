// Small line plots rasterised to RGB images (log-log for `sonarsim study`, linear for `sonarsim compare`); no
// GL, no dependencies.
#pragma once
#include "core/display/image.hpp"

#include <array>
#include <string>
#include <vector>

namespace sonarsim::app {

struct Series {
    std::string name;
    std::array<std::uint8_t, 3> rgb;
    std::vector<std::pair<double, double>> points; ///< (x, y), both > 0
};

Image8 loglog_plot(const std::vector<Series>& series, const std::string& title, const std::string& x_label,
                   const std::string& y_label, int width = 900, int height = 600);

/// The same with linear axes (any finite x, y; ticks at round steps).
Image8 linear_plot(const std::vector<Series>& series, const std::string& title, const std::string& x_label,
                   const std::string& y_label, int width = 900, int height = 600);

/// Images of the same width stacked top to bottom.
Image8 stack_vertically(const std::vector<Image8>& images);

} // namespace sonarsim::app

// A small log-log line plot rasterised to an RGB image (for `sonarsim study`); no GL, no dependencies.
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

} // namespace sonarsim::app

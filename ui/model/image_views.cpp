#include "ui/model/image_views.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace sonarsim::ui {

Image8 polar_color_image(const PolarImage& img, const DisplayParams& d) {
    // As the fan does it: the gray level rounded to one of 256, through the map's 256 colours (a table).
    const auto lut = colormap_table(d.colormap);
    const std::array<std::uint8_t, 3> none = no_echo_rgb(d.colormap);
    Image8 out;
    out.width = img.beams, out.height = img.bins, out.channels = 3;
    out.pixels.resize(size_t(img.beams) * size_t(img.bins) * 3);
    tbb::parallel_for(tbb::blocked_range<int>(0, img.bins, 64), [&](const tbb::blocked_range<int>& bins) {
        for (int b = bins.begin(); b < bins.end(); ++b) {
            std::uint8_t* row = out.pixels.data() + size_t(img.bins - 1 - b) * size_t(img.beams) * 3;
            for (int i = 0; i < img.beams; ++i, row += 3) {
                const float v = img.at(b, i);
                const auto& c =
                    v > -INFINITY ? lut[size_t(int(gray_level(v, d.lo_db, d.hi_db) + 0.5f))] : none;
                row[0] = c[0], row[1] = c[1], row[2] = c[2];
            }
        }
    });
    return out;
}

Image8 fan_with_no_echo(const Frame& f, Colormap map) {
    if (!f.sector_map_ptr) throw std::invalid_argument("fan_with_no_echo: the frame has no fan map");
    Image8 out = f.sector();
    f.sector_map_ptr->paint_no_echo(f.polar(), no_echo_rgb(map), out);
    return out;
}

int beam_at_azimuth(double az, const SonarGrid& grid) {
    return grid.beam_of_azimuth_deg(az);
}

double nice_step(double span, int count) {
    if (!(span > 0) || count < 1) return 1;
    const double raw = span / count, p = std::pow(10.0, std::floor(std::log10(raw))), m = raw / p;
    return (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10) * p;
}

std::vector<float> beam_levels(const PolarImage& img, int beam) {
    std::vector<float> v;
    if (beam < 0 || beam >= img.beams) return v;
    v.reserve(size_t(img.bins));
    for (int b = 0; b < img.bins; ++b) v.push_back(img.at(b, beam));
    return v;
}

int strongest_beam(const PolarImage& img) {
    int best = img.beams / 2;
    float top = -INFINITY;
    for (int b = 0; b < img.bins; ++b)
        for (int i = 0; i < img.beams; ++i)
            if (img.at(b, i) > top) top = img.at(b, i), best = i;
    return best;
}

} // namespace sonarsim::ui

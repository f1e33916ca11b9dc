#include "ui/model/image_views.hpp"

#include "ui/model/sonar_geometry.hpp"

#include <algorithm>
#include <cmath>

namespace sonarsim::ui {

Image8 polar_color_image(const PolarImage& img, const DisplayParams& d) {
    Image8 out;
    out.width = img.beams, out.height = img.bins, out.channels = 3;
    out.pixels.resize(size_t(img.beams) * img.bins * 3);
    for (int b = 0; b < img.bins; ++b)
        for (int i = 0; i < img.beams; ++i) {
            const float v = img.at(b, i);
            const auto c = v > -INFINITY ? colormap_rgb(d.colormap, gray_level(v, d.lo_db, d.hi_db) / 255.0)
                                         : no_echo_rgb(d.colormap);
            std::copy(c.begin(), c.end(),
                      out.pixels.begin() + long((size_t(img.bins - 1 - b) * img.beams + i) * 3));
        }
    return out;
}

Image8 NoEchoPainter::paint(const Image8& fan, const PolarImage& img, const SonarParams& s, Colormap map) {
    std::shared_ptr<const SonarGrid> grid = sonar_grid(s);
    const bool same = w_ == fan.width && h_ == fan.height && key_ == grid;
    if (!same) {
        const SectorLayout L(grid, fan.height);
        cell_.assign(size_t(fan.width) * size_t(fan.height), -1);
        for (int y = 0; y < fan.height; ++y)
            for (int x = 0; x < fan.width; ++x) {
                double r = 0, a = 0;
                if (!L.pixel_to_polar(x + 0.5, y + 0.5, r, a)) continue;
                int bin = 0, beam = 0;
                if (polar_to_cell(s, r, a, bin, beam))
                    cell_[size_t(y) * size_t(fan.width) + size_t(x)] = bin * s.beams + beam;
            }
        key_ = std::move(grid), w_ = fan.width, h_ = fan.height;
    }
    Image8 out = fan;
    if (out.channels != 3 || img.beams != s.beams || img.bins != s.range_bins) return out;
    const auto c = no_echo_rgb(map);
    for (size_t p = 0; p < cell_.size(); ++p)
        if (cell_[p] >= 0 && !(img.level_db[size_t(cell_[p])] > -INFINITY))
            std::copy(c.begin(), c.end(), out.pixels.begin() + long(p * 3));
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

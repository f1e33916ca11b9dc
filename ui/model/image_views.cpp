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

Image8 fan_with_no_echo(const Frame& f, Colormap map) {
    Image8 out = f.sector();
    const std::shared_ptr<const SectorResampler> taps =
        f.sector_map_ptr ? f.sector_map_ptr : std::make_shared<const SectorResampler>(f.grid_ptr, out.height);
    taps->paint_no_echo(f.polar(), no_echo_rgb(map), out);
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

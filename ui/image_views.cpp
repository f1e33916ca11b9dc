#include "image_views.hpp"

#include <cmath>

namespace sonarsim::ui {

Image8 polar_color_image(const PolarImage& img, const DisplayParams& d) {
    Image8 out;
    out.width = img.beams, out.height = img.bins, out.channels = 3;
    out.pixels.resize(size_t(img.beams) * img.bins * 3);
    for (int b = 0; b < img.bins; ++b)
        for (int i = 0; i < img.beams; ++i) {
            const auto c = colormap_rgb(d.colormap, gray_level(img.at(b, i), d.lo_db, d.hi_db) / 255.0);
            std::copy(c.begin(), c.end(),
                      out.pixels.begin() + long((size_t(img.bins - 1 - b) * img.beams + i) * 3));
        }
    return out;
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

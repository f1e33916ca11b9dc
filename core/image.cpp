#include "image.hpp"

#include "pose.hpp"

#include <algorithm>
#include <cmath>

namespace sonarsim {

float gray_level(float level_db, double lo, double hi) {
    if (!(level_db > -INFINITY)) return 0.0f;
    return float(255.0 * std::clamp((double(level_db) - lo) / (hi - lo), 0.0, 1.0));
}

std::array<std::uint8_t, 3> colormap_rgb(Colormap map, double t) {
    t = std::clamp(t, 0.0, 1.0);
    if (map == Colormap::Gray) {
        const auto g = std::uint8_t(std::lround(255 * t));
        return {g, g, g};
    }
    // Viridis, sampled at nine evenly spaced points and interpolated linearly.
    static const double v[9][3] = {{68, 1, 84},    {71, 44, 122},  {59, 81, 139},
                                   {44, 113, 142}, {33, 144, 141}, {39, 173, 129},
                                   {92, 200, 99},  {170, 220, 50}, {253, 231, 37}};
    const double x = t * 8;
    const int i = std::min(7, int(x));
    const double f = x - i;
    std::array<std::uint8_t, 3> c{};
    for (int k = 0; k < 3; ++k) c[size_t(k)] = std::uint8_t(std::lround(v[i][k] * (1 - f) + v[i + 1][k] * f));
    return c;
}

Image8 polar_gray_image(const PolarImage& img, const DisplayParams& d) {
    Image8 out;
    out.width = img.beams, out.height = img.bins, out.channels = 1;
    out.pixels.resize(size_t(img.beams) * img.bins);
    for (int b = 0; b < img.bins; ++b)
        for (int i = 0; i < img.beams; ++i)
            out.pixels[size_t(img.bins - 1 - b) * img.beams + i] =
                std::uint8_t(std::lround(gray_level(img.at(b, i), d.lo_db, d.hi_db)));
    return out;
}

int default_sector_height(const SonarParams& s) {
    return std::clamp(s.range_bins, 256, 2048);
}

SectorLayout::SectorLayout(const SonarParams& s, int height_px) : s_(s) {
    const double half = deg2rad(s.azimuth_fov_deg / 2);
    y0_m_ = s.range_min_m * std::cos(half);
    height_ = std::max(16, height_px);
    m_per_px_ = (s.range_max_m - y0_m_) / height_;
    width_ = std::max(16, int(std::ceil(2 * s.range_max_m * std::sin(half) / m_per_px_)));
}

bool SectorLayout::pixel_to_polar(double px, double py, double& r, double& a_deg) const {
    const double x = (px - width_ / 2.0) * m_per_px_, y = (height_ - py) * m_per_px_ + y0_m_;
    r = std::hypot(x, y);
    a_deg = rad2deg(std::atan2(-x, y));
    return r >= s_.range_min_m && r < s_.range_max_m && std::abs(a_deg) <= s_.azimuth_fov_deg / 2;
}

void SectorLayout::polar_to_pixel(double r, double a_deg, double& px, double& py) const {
    const double a = deg2rad(a_deg);
    px = width_ / 2.0 - r * std::sin(a) / m_per_px_;
    py = height_ - (r * std::cos(a) - y0_m_) / m_per_px_;
}

void SectorLayout::polar_to_index(double r, double a_deg, double& bin, double& beam) const {
    bin = (r - s_.range_min_m) / ((s_.range_max_m - s_.range_min_m) / s_.range_bins) - 0.5;
    beam = (s_.azimuth_fov_deg / 2 - a_deg) / (s_.azimuth_fov_deg / s_.beams) - 0.5;
}

Image8 sector_image(const PolarImage& img, const SonarParams& s, const DisplayParams& d, int height_px) {
    const SectorLayout L(s, height_px > 0 ? height_px : default_sector_height(s));
    std::vector<float> gray(img.level_db.size());
    for (size_t n = 0; n < gray.size(); ++n) gray[n] = gray_level(img.level_db[n], d.lo_db, d.hi_db);

    Image8 out;
    out.width = L.width(), out.height = L.height(), out.channels = 3;
    out.pixels.resize(size_t(out.width) * out.height * 3);
    for (int py = 0; py < out.height; ++py)
        for (int px = 0; px < out.width; ++px) {
            std::array<std::uint8_t, 3> c = kFanBackground;
            double r, a;
            if (L.pixel_to_polar(px + 0.5, py + 0.5, r, a)) {
                double fb, fi;
                L.polar_to_index(r, a, fb, fi);
                fb = std::clamp(fb, 0.0, img.bins - 1.0), fi = std::clamp(fi, 0.0, img.beams - 1.0);
                const int b0 = std::min(int(fb), img.bins - 1), i0 = std::min(int(fi), img.beams - 1);
                const int b1 = std::min(b0 + 1, img.bins - 1), i1 = std::min(i0 + 1, img.beams - 1);
                const double tb = fb - b0, ti = fi - i0;
                auto g = [&](int b, int i) { return double(gray[size_t(b) * img.beams + i]); };
                const double v = (1 - tb) * ((1 - ti) * g(b0, i0) + ti * g(b0, i1)) +
                                 tb * ((1 - ti) * g(b1, i0) + ti * g(b1, i1));
                c = colormap_rgb(d.colormap, v / 255.0);
            }
            std::copy(c.begin(), c.end(), out.pixels.begin() + (size_t(py) * out.width + px) * 3);
        }
    return out;
}

} // namespace sonarsim

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

SectorResampler::SectorResampler(const SonarParams& s, int height_px)
    : sonar_(s), height_px_(height_px), layout_(s, height_px > 0 ? height_px : default_sector_height(s)) {
    const int W = layout_.width(), H = layout_.height(), K = s.range_bins, N = s.beams;
    taps_.resize(size_t(W) * H);
    for (int py = 0; py < H; ++py)
        for (int px = 0; px < W; ++px) {
            double r, a, fb, fi;
            if (!layout_.pixel_to_polar(px + 0.5, py + 0.5, r, a)) continue;
            layout_.polar_to_index(r, a, fb, fi);
            fb = std::clamp(fb, 0.0, K - 1.0), fi = std::clamp(fi, 0.0, N - 1.0);
            const int b0 = std::min(int(fb), K - 1), i0 = std::min(int(fi), N - 1);
            Tap& t = taps_[size_t(py) * W + px];
            t.index = b0 * N + i0;
            t.step_bin = b0 + 1 < K ? N : 0, t.step_beam = i0 + 1 < N ? 1 : 0;
            t.tb = float(fb - b0), t.ti = float(fi - i0);
        }
}

bool SectorResampler::matches(const SonarParams& s, int height_px) const {
    return height_px == height_px_ && s.beams == sonar_.beams && s.range_bins == sonar_.range_bins &&
           s.azimuth_fov_deg == sonar_.azimuth_fov_deg && s.range_min_m == sonar_.range_min_m &&
           s.range_max_m == sonar_.range_max_m;
}

Image8 SectorResampler::apply(const PolarImage& img, const DisplayParams& d) const {
    std::vector<float> gray(img.level_db.size());
    for (size_t n = 0; n < gray.size(); ++n) gray[n] = gray_level(img.level_db[n], d.lo_db, d.hi_db);
    std::array<std::array<std::uint8_t, 3>, 256> lut;
    for (int g = 0; g < 256; ++g) lut[size_t(g)] = colormap_rgb(d.colormap, g / 255.0);

    Image8 out;
    out.width = layout_.width(), out.height = layout_.height(), out.channels = 3;
    out.pixels.resize(taps_.size() * 3);
    for (size_t p = 0; p < taps_.size(); ++p) {
        const Tap& t = taps_[p];
        std::array<std::uint8_t, 3> c = kFanBackground;
        if (t.index >= 0) {
            const float* g = gray.data() + t.index;
            const float v = (1 - t.tb) * ((1 - t.ti) * g[0] + t.ti * g[t.step_beam]) +
                            t.tb * ((1 - t.ti) * g[t.step_bin] + t.ti * g[t.step_bin + t.step_beam]);
            c = lut[size_t(std::clamp(int(std::lround(v)), 0, 255))];
        }
        std::copy(c.begin(), c.end(), out.pixels.begin() + long(p) * 3);
    }
    return out;
}

Image8 sector_image(const PolarImage& img, const SonarParams& s, const DisplayParams& d, int height_px) {
    return SectorResampler(s, height_px).apply(img, d);
}

} // namespace sonarsim

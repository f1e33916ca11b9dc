#include "core/scene/sonar_grid.hpp"

#include "core/base/shared_registry.hpp"

#include <tuple>

namespace sonarsim {

std::vector<double> SonarGrid::beam_azimuths_deg() const {
    std::vector<double> a(static_cast<size_t>(beams));
    for (int i = 0; i < beams; ++i) a[size_t(i)] = beam_azimuth_deg(i);
    return a;
}

std::vector<double> SonarGrid::bin_edges_m() const {
    std::vector<double> e(static_cast<size_t>(bins) + 1);
    for (int k = 0; k <= bins; ++k) e[size_t(k)] = range_min_m + k * bin_m;
    e.back() = range_max_m;
    return e;
}

double SonarGrid::fan_width_px(double height_px) const {
    const double m_per_px = (range_max_m - range_min_m * std::cos(fan_half_rad)) / height_px;
    return std::max(16.0, std::ceil(2 * range_max_m * std::sin(fan_half_rad) / m_per_px));
}

FanLayout SonarGrid::fan_layout(int height_px) const {
    FanLayout f;
    f.y0_m = range_min_m * std::cos(fan_half_rad);
    f.height_px = std::max(16, height_px);
    f.m_per_px = (range_max_m - f.y0_m) / f.height_px;
    f.width_px = std::max(16, int(std::ceil(2 * range_max_m * std::sin(fan_half_rad) / f.m_per_px)));
    return f;
}

int SonarGrid::default_fan_height_px() const {
    int h = std::clamp(bins, 256, 2048);
    // Width per height of the layout: 2 r_max sin(half) / (r_max - r_min cos(half)).
    const double ratio =
        2 * range_max_m * std::sin(fan_half_rad) / (range_max_m - range_min_m * std::cos(fan_half_rad));
    if (std::ceil(h * ratio) > kMaxFanWidthPx) h = std::max(16, int(std::floor(kMaxFanWidthPx / ratio)));
    return h;
}

double SonarGrid::fan_pixels_unbounded() const {
    const double height = std::clamp(bins, 256, 2048);
    return fan_width_px(height) * height;
}

std::shared_ptr<const SonarGrid> sonar_grid(const SonarParams& s) {
    using Key = std::tuple<int, int, double, double, double>;
    static SharedRegistry<Key, SonarGrid> registry;
    return registry.get(Key{s.beams, s.range_bins, s.range_min_m, s.range_max_m, s.azimuth_fov_deg},
                        [&] { return std::make_shared<const SonarGrid>(s); });
}

} // namespace sonarsim

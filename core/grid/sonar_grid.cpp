#include "core/grid/sonar_grid.hpp"

#include "core/base/errors.hpp"
#include "core/base/shared_registry.hpp"

#include <string>
#include <tuple>

namespace sonarsim {

SonarGrid::SonarGrid(const SonarParams& s)
    : beams(s.beams), bins(s.range_bins), range_min_m(s.range_min_m), range_max_m(s.range_max_m),
      bin_m(range_bin_m(s)), fov_deg(s.azimuth_fov_deg),
      fov_rad(s.azimuth_fov_deg * 3.14159265358979323846 / 180), spacing_rad(fov_rad / s.beams),
      fan_half_rad(s.azimuth_fov_deg / 2 * 3.14159265358979323846 / 180),
      elevation_fov_deg(s.elevation_fov_deg) {
    if (s.beam_table == kUniformBeams) return;
    if (const std::string problem = beam_table_problem(s); !problem.empty())
        throw InputError("", "sonar.beam_table", problem);
    table_ = find_beam_table(s.beam_table);
    constexpr double to_rad = 3.14159265358979323846 / 180;
    for (int i = 0; i < beams; ++i) {
        centre_rad_.push_back(table_->centre_deg[size_t(i)] * to_rad);
        port_rad_.push_back(table_->port_edge_deg[size_t(i)] * to_rad);
        stbd_rad_.push_back(table_->starboard_edge_deg[size_t(i)] * to_rad);
    }
    narrowest_rad_ = widest_rad_ = beam_width_rad(0);
    for (int i = 1; i < beams; ++i)
        narrowest_rad_ = std::min(narrowest_rad_, beam_width_rad(i)),
        widest_rad_ = std::max(widest_rad_, beam_width_rad(i));
    fov_deg = table_->port_edge_deg.front() - table_->starboard_edge_deg.back();
    fov_rad = fov_deg * to_rad;
    spacing_rad = fov_rad / beams;
    fan_half_rad = std::max(std::abs(port_rad_.front()), std::abs(stbd_rad_.back()));
    // Four buckets per beam on average: beam_of_stbd_rad rarely steps more than one beam.
    bucket_beam_.resize(size_t(4 * beams));
    buckets_per_rad_ = double(bucket_beam_.size()) / fov_rad;
    for (size_t b = 0; b < bucket_beam_.size(); ++b)
        bucket_beam_[b] = beam_of_table(port_rad_.front() - double(b) / buckets_per_rad_, stbd_rad_);
}

std::string beam_table_problem(const SonarParams& s) {
    if (s.beam_table == kUniformBeams) return "";
    std::string names = std::string(kUniformBeams);
    for (const std::string& n : beam_table_names()) names += ", " + n;
    const BeamTable* t = find_beam_table(s.beam_table);
    if (!t) return "unknown beam table '" + s.beam_table + "'; allowed: " + names;
    if (t->beams() != s.beams) {
        std::string fitting = std::string(kUniformBeams);
        for (const std::string& n : beam_table_names())
            if (find_beam_table(n)->beams() == s.beams) fitting += ", " + n;
        return "the table '" + s.beam_table + "' has " + std::to_string(t->beams()) +
               " beams, sonar.beams is " + std::to_string(s.beams) + "; allowed for " +
               std::to_string(s.beams) + " beams: " + fitting;
    }
    return "";
}

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
    using Key = std::tuple<int, int, double, double, double, double, std::string>;
    static SharedRegistry<Key, SonarGrid> registry;
    return registry.get(Key{s.beams, s.range_bins, s.range_min_m, s.range_max_m, s.azimuth_fov_deg,
                            s.elevation_fov_deg, s.beam_table},
                        [&] { return std::make_shared<const SonarGrid>(s); });
}

} // namespace sonarsim

#include "ui/model/measure.hpp"

#include "core/data/pose.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace sonarsim::ui {

double image_distance_m(const ImagePlace& a, const ImagePlace& b) {
    const double ta = a.azimuth_deg * kPi / 180, tb = b.azimuth_deg * kPi / 180;
    return std::hypot(a.range_m * std::cos(ta) - b.range_m * std::cos(tb),
                      a.range_m * std::sin(ta) - b.range_m * std::sin(tb));
}

RegionStats region_stats(const PolarImage& img, const SonarParams& s, const ImagePlace& a,
                         const ImagePlace& b) {
    const double r0 = std::min(a.range_m, b.range_m), r1 = std::max(a.range_m, b.range_m);
    const double a0 = std::min(a.azimuth_deg, b.azimuth_deg), a1 = std::max(a.azimuth_deg, b.azimuth_deg);
    const std::shared_ptr<const SonarGrid> grid = sonar_grid(s);
    RegionStats st;
    if (img.bins != grid->bins || img.beams != grid->beams) return st;
    std::vector<double> levels;
    double sum = 0;
    for (int bin = 0; bin < img.bins; ++bin) {
        const double r = grid->bin_centre_m(bin);
        if (r < r0 || r > r1) continue;
        for (int beam = 0; beam < img.beams; ++beam) {
            const double az = grid->beam_azimuth_deg(beam);
            if (az < a0 || az > a1) continue;
            ++st.cells;
            const float v = img.at(bin, beam);
            if (!std::isfinite(v)) continue;
            levels.push_back(v);
            sum += std::pow(10.0, v / 10.0);
        }
    }
    st.echo_cells = int(levels.size());
    if (levels.empty()) return st;
    std::sort(levels.begin(), levels.end());
    st.min_db = levels.front(), st.max_db = levels.back();
    const size_t n = levels.size();
    st.median_db = n % 2 ? levels[n / 2] : 0.5 * (levels[n / 2 - 1] + levels[n / 2]);
    st.mean_db = 10 * std::log10(sum / double(n));
    return st;
}

} // namespace sonarsim::ui

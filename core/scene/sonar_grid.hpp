// The sonar's image grid: its beams across azimuth and its range bins, built once from the table's values
// and passed to every stage and to the viewer instead of re-deriving widths and angles at each call site.
// Beam 0 is port-most (positive azimuth), bin 0 nearest. A device with non-uniform beam angles changes this
// type alone: beam angles come from the grid, never from a formula at the call site.
#pragma once
#include "core/scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace sonarsim {

class SonarGrid {
  public:
    explicit SonarGrid(const SonarParams& s)
        : beams(s.beams), bins(s.range_bins), range_min_m(s.range_min_m), range_max_m(s.range_max_m),
          bin_m((s.range_max_m - s.range_min_m) / s.range_bins), fov_deg(s.azimuth_fov_deg),
          fov_rad(s.azimuth_fov_deg * 3.14159265358979323846 / 180), spacing_rad(fov_rad / s.beams) {}

    int beams, bins;
    double range_min_m, range_max_m;
    double bin_m;       ///< width of a range bin [m]
    double fov_deg;     ///< azimuth field of view Theta [deg]
    double fov_rad;     ///< Theta [rad]
    double spacing_rad; ///< Theta / N [rad]

    /// Azimuth of beam i's centre [deg]: Theta/2 - (i + 1/2) Theta / N (eq. 10).
    double beam_azimuth_deg(int i) const { return fov_deg / 2 - (i + 0.5) * fov_deg / beams; }
    /// Azimuth of beam i's centre [rad].
    double beam_azimuth_rad(int i) const { return fov_rad / 2 - (i + 0.5) * spacing_rad; }
    /// Azimuth of beam i's port (upper) edge [rad]; beam i covers [edge - spacing, edge].
    double beam_port_edge_rad(int i) const { return fov_rad / 2 - i * spacing_rad; }
    /// The beam whose slice holds azimuth a [deg], clamped to the fan (callers check inside() first).
    int beam_of_azimuth_deg(double a_deg) const {
        return int(std::clamp(std::floor((fov_deg / 2 - a_deg) / (fov_deg / beams)), 0.0, double(beams - 1)));
    }
    /// Centre of range bin b [m].
    double bin_centre_m(int b) const { return range_min_m + (b + 0.5) * bin_m; }
    /// The bin holding range r, clamped to the window (callers check inside() first).
    int bin_of(double r_m) const {
        return std::clamp(int(std::floor((r_m - range_min_m) / bin_m)), 0, bins - 1);
    }
    /// True when range r [m] and azimuth a [deg] lie in the image.
    bool inside(double r_m, double a_deg) const {
        return r_m >= range_min_m && r_m < range_max_m && std::abs(a_deg) <= fov_deg / 2;
    }
    /// Every beam's centre azimuth [deg].
    std::vector<double> beam_azimuths_deg() const {
        std::vector<double> a(static_cast<size_t>(beams));
        for (int i = 0; i < beams; ++i) a[size_t(i)] = beam_azimuth_deg(i);
        return a;
    }
    /// The K + 1 bin edges [m] over [r_min, r_max].
    std::vector<double> bin_edges_m() const {
        std::vector<double> e(static_cast<size_t>(bins) + 1);
        for (int k = 0; k <= bins; ++k) e[size_t(k)] = range_min_m + k * bin_m;
        e.back() = range_max_m;
        return e;
    }
};

} // namespace sonarsim

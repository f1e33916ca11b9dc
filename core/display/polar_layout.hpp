// The raw (polar) image laid out in a rectangle, beside SectorLayout for the fan: beams across (port left,
// each beam as wide as its share of the fan), range bins down with the far edge at the top (as the fan
// shows it). The one place the raw view's range and azimuth map to a position and back.
#pragma once
#include "core/grid/sonar_grid.hpp"

namespace sonarsim {

class PolarLayout {
  public:
    explicit PolarLayout(const SonarGrid& grid) : grid_(grid) {}
    /// Fraction across the image [0, 1] of azimuth a [deg]: 0 at the port edge.
    double u_of_azimuth_deg(double a_deg) const { return grid_.column_of_azimuth_deg(a_deg) / grid_.beams; }
    /// Fraction down the image [0, 1] of range r [m]: 0 at r_max (the top), 1 at r_min.
    double v_of_range_m(double r_m) const { return (grid_.range_max_m - r_m) / grid_.window_m(); }
    /// Azimuth [deg] at fraction u across.
    double azimuth_deg_at(double u) const { return grid_.column_azimuth_deg(u * grid_.beams); }
    /// Range [m] at fraction v down.
    double range_m_at(double v) const { return grid_.range_max_m - v * grid_.window_m(); }

  private:
    const SonarGrid& grid_;
};

} // namespace sonarsim

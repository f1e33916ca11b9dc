// The sonar's image grid: its beams across azimuth, its range bins and the fan they are laid out as, built
// once per scene change (`sonar_grid`, shared) and passed to every stage and to the viewer instead of
// re-deriving widths and angles at each call site. Beam 0 is port-most (positive azimuth), bin 0 nearest.
// Beams are evenly spaced over Theta (eq. 10), or each beam's centre and edges come from a device's table
// (`sonar.beam_table`, beam_tables.hpp). Beam angles come from the grid, never from a formula at the
// call site.
#pragma once
#include "core/grid/beam_tables.hpp"
#include "core/data/pose.hpp"
#include "core/data/scene.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

namespace sonarsim {

/// Widest default fan image [px]: a texture width every OpenGL implementation takes.
constexpr int kMaxFanWidthPx = 4096;

/// The fan image's geometry: apex at the bottom centre, range up, port (positive azimuth) left.
struct FanLayout {
    int width_px = 0, height_px = 0;
    double m_per_px = 0; ///< metres per pixel, both ways
    double y0_m = 0;     ///< forward distance of the bottom row's lower edge: r_min cos(half the fan)
};

/// The range window r_max - r_min [m] and a range bin's width [m] of a sonar, for what needs them before a
/// grid exists (input validation); a grid has them as window_m() and bin_m.
inline double range_window_m(const SonarParams& s) {
    return s.range_max_m - s.range_min_m;
}
inline double range_bin_m(const SonarParams& s) {
    return range_window_m(s) / s.range_bins;
}

class SonarGrid {
  public:
    /// Throws InputError (key sonar.beam_table) for an unknown table or one of another beam count.
    explicit SonarGrid(const SonarParams& s);

    int beams, bins;
    double range_min_m, range_max_m;
    double bin_m;   ///< width of a range bin [m]
    double fov_deg; ///< azimuth field of view Theta: port edge of beam 0 - starboard edge of beam N-1 [deg]
    double fov_rad; ///< Theta [rad]
    double spacing_rad;       ///< Theta / N [rad]: the mean beam width
    double fan_half_rad;      ///< half the fan's opening [rad]: the widest |azimuth| of any beam edge
    double elevation_fov_deg; ///< the elevation aperture [deg], centred on the sonar's axis

    /// r_max - r_min [m].
    double window_m() const { return range_max_m - range_min_m; }
    /// The middle of the range window [m].
    double window_middle_m() const { return 0.5 * (range_min_m + range_max_m); }
    /// Half the elevation aperture [deg]: the beam's upper edge (its lower is the negative).
    double elevation_half_deg() const { return elevation_fov_deg / 2; }
    /// True when elevation e [deg] lies in the aperture.
    bool in_elevation_deg(double e_deg) const { return std::abs(e_deg) <= elevation_half_deg() + 1e-9; }
    /// True when `o` has the same beams and bins (it may differ in the elevation aperture alone): the image,
    /// the fan and its resampling taps are the same.
    bool same_image(const SonarGrid& o) const {
        return beams == o.beams && bins == o.bins && range_min_m == o.range_min_m &&
               range_max_m == o.range_max_m && fov_deg == o.fov_deg && table_ == o.table_;
    }

    /// The table the beams come from, or null when they are evenly spaced.
    const BeamTable* table() const { return table_; }
    bool uniform() const { return table_ == nullptr; }

    /// Azimuth of beam i's centre [deg]: Theta/2 - (i + 1/2) Theta / N (eq. 10), or the table's.
    double beam_azimuth_deg(int i) const {
        return table_ ? table_->centre_deg[size_t(i)] : fov_deg / 2 - (i + 0.5) * fov_deg / beams;
    }
    /// Azimuth of beam i's centre [rad].
    double beam_azimuth_rad(int i) const {
        return table_ ? centre_rad_[size_t(i)] : fov_rad / 2 - (i + 0.5) * spacing_rad;
    }
    /// Azimuth of beam i's port (upper) edge [rad]; beam i covers [starboard edge, port edge].
    double beam_port_edge_rad(int i) const {
        return table_ ? port_rad_[size_t(i)] : fov_rad / 2 - i * spacing_rad;
    }
    /// Azimuth of beam i's starboard (lower) edge [rad].
    double beam_starboard_edge_rad(int i) const {
        return table_ ? stbd_rad_[size_t(i)] : fov_rad / 2 - (i + 1.0) * fov_rad / beams;
    }
    /// Width of beam i: port edge - starboard edge [rad].
    double beam_width_rad(int i) const {
        return table_ ? port_rad_[size_t(i)] - stbd_rad_[size_t(i)] : spacing_rad;
    }
    /// Width of beam i [deg].
    double beam_width_deg(int i) const {
        return table_ ? table_->port_edge_deg[size_t(i)] - table_->starboard_edge_deg[size_t(i)]
                      : fov_deg / beams;
    }
    /// Relative response of beam i (the table's gain; 1 for even beams).
    double beam_gain(int i) const { return table_ ? table_->gain[size_t(i)] : 1.0; }
    /// The narrowest and the widest beam [rad].
    double narrowest_beam_rad() const { return table_ ? narrowest_rad_ : spacing_rad; }
    double widest_beam_rad() const { return table_ ? widest_rad_ : spacing_rad; }
    /// The fan's port and starboard edges [deg]: beam 0's port edge, the last beam's starboard edge (a
    /// table's fan need not be symmetric: the DIDSON's spans -14.72 ... +14.09 deg).
    double port_edge_deg() const { return rad2deg(beam_port_edge_rad(0)); }
    double starboard_edge_deg() const { return rad2deg(beam_starboard_edge_rad(beams - 1)); }
    /// Half the azimuth aperture the sonar sees [rad] (the widest side of the fan).
    double half_aperture_rad() const { return table_ ? fan_half_rad : fov_rad / 2; }
    /// Centre of fine column j when each beam is split into `per_beam` equal columns [rad]; column 0 is the
    /// port-most.
    double column_azimuth_rad(int j, int per_beam) const {
        if (!table_) return fov_rad / 2 - (j + 0.5) * spacing_rad / per_beam;
        const int b = j / per_beam;
        return port_rad_[size_t(b)] - (j % per_beam + 0.5) * beam_width_rad(b) / per_beam;
    }
    /// The beam whose slice holds azimuth a [deg], clamped to the fan (callers check inside() first).
    int beam_of_azimuth_deg(double a_deg) const {
        if (table_) return beam_of_table(a_deg, table_->starboard_edge_deg);
        return int(std::clamp(std::floor((fov_deg / 2 - a_deg) / (fov_deg / beams)), 0.0, double(beams - 1)));
    }
    /// The beam whose slice holds azimuth a [rad], clamped to the fan.
    int beam_of_azimuth_rad(double a_rad) const {
        if (table_) return beam_of_stbd_rad(a_rad);
        return std::clamp(int(std::floor((fov_rad / 2 - a_rad) / spacing_rad)), 0, beams - 1);
    }
    /// Fractional beam index of azimuth a [deg], beam centres at integers, linear between them (the fan's
    /// interpolation coordinate; not clamped).
    double beam_index_of_azimuth_deg(double a_deg) const {
        if (!table_) return (fov_deg / 2 - a_deg) / (fov_deg / beams) - 0.5;
        const std::vector<double>& c = table_->centre_deg;                   // descending
        const int i = std::clamp(beam_of_table(a_deg, c), 1, beams - 1) - 1; // c[i] >= a > c[i + 1] inside
        return i + (c[size_t(i)] - a_deg) / (c[size_t(i)] - c[size_t(i) + 1]);
    }
    /// The same, cheaper for azimuths visited in decreasing order (a fan's row from port to starboard):
    /// `hint` is the table index the previous call ended at (start at 0); it walks from there instead of
    /// a binary search.
    double beam_index_of_azimuth_deg(double a_deg, int& hint) const {
        if (!table_) return beam_index_of_azimuth_deg(a_deg);
        // Descending centres: the first c[j] <= a, as beam_of_table finds it (walking back first keeps any
        // order of calls exact).
        const std::vector<double>& c = table_->centre_deg;
        while (hint > 0 && c[size_t(hint) - 1] <= a_deg) --hint;
        while (hint < beams && c[size_t(hint)] > a_deg) ++hint;
        const int i = std::clamp(std::min(hint, beams - 1), 1, beams - 1) - 1;
        return i + (c[size_t(i)] - a_deg) / (c[size_t(i)] - c[size_t(i) + 1]);
    }
    /// Azimuth at continuous column x of the raw image (beam i spans columns [i, i + 1), column 0 at the
    /// port edge) [deg].
    double column_azimuth_deg(double x) const {
        if (!table_) return fov_deg / 2 - x * fov_deg / beams;
        const int i = std::clamp(int(std::floor(x)), 0, beams - 1);
        return table_->port_edge_deg[size_t(i)] - (x - i) * beam_width_deg(i);
    }
    /// Continuous raw-image column of azimuth a [deg] (the inverse of column_azimuth_deg).
    double column_of_azimuth_deg(double a_deg) const {
        if (!table_) return (fov_deg / 2 - a_deg) / fov_deg * beams;
        const int i = beam_of_azimuth_deg(a_deg);
        return i + (table_->port_edge_deg[size_t(i)] - a_deg) / beam_width_deg(i);
    }
    /// Centre of range bin b [m].
    double bin_centre_m(int b) const { return range_min_m + (b + 0.5) * bin_m; }
    /// Near edge of range bin b [m] (b = bins: the far edge of the last).
    double bin_near_edge_m(int b) const { return range_min_m + b * bin_m; }
    /// Range at continuous bin coordinate u [m] (0: the near edge of bin 0; bins: the far edge).
    double range_at_bin_m(double u) const { return range_min_m + u * bin_m; }
    /// Continuous bin coordinate of range r, unclamped (the inverse of range_at_bin_m; its floor is r's
    /// bin when inside the window).
    double bin_position(double r_m) const { return (r_m - range_min_m) / bin_m; }
    /// The bin holding range r, clamped to the window (callers check inside() first).
    int bin_of(double r_m) const {
        return std::clamp(int(std::floor((r_m - range_min_m) / bin_m)), 0, bins - 1);
    }
    /// True when azimuth a [deg] lies in the fan.
    bool inside_fan_deg(double a_deg) const {
        return table_ ? a_deg <= table_->port_edge_deg.front() && a_deg >= table_->starboard_edge_deg.back()
                      : std::abs(a_deg) <= fov_deg / 2;
    }
    /// True when range r [m] and azimuth a [deg] lie in the image.
    bool inside(double r_m, double a_deg) const {
        return r_m >= range_min_m && r_m < range_max_m && inside_fan_deg(a_deg);
    }
    /// Every beam's centre azimuth [deg].
    std::vector<double> beam_azimuths_deg() const;
    /// The K + 1 bin edges [m] over [r_min, r_max].
    std::vector<double> bin_edges_m() const;

    /// The fan laid out `height_px` rows high (at least 16 px each way).
    FanLayout fan_layout(int height_px) const;
    /// Default fan height [px]: the number of range bins, kept within [256, 2048] (one pixel row per bin up
    /// to 2048 bins), and lowered where needed so that the width stays within kMaxFanWidthPx.
    int default_fan_height_px() const;
    /// Pixels of the fan at the height of one row per bin in [256, 2048], in double precision so that
    /// absurd windows give a large number instead of an int overflow (input validation).
    double fan_pixels_unbounded() const;

  private:
    /// Width of the fan at `height_px` rows [px], in double precision.
    double fan_width_px(double height_px) const;
    /// The first beam whose lower value in `lower` (descending) is at most a, clamped to [0, N - 1].
    int beam_of_table(double a, const std::vector<double>& lower) const {
        const auto it =
            std::lower_bound(lower.begin(), lower.end(), a, [](double v, double x) { return v > x; });
        return std::min(int(it - lower.begin()), beams - 1);
    }
    /// beam_of_table(a, stbd_rad_) (multipath asks it for each mixed ghost): from the beam the bucket index
    /// gives for a, stepped to the one whose lower edge is the first at most a; the same answer for every a.
    int beam_of_stbd_rad(double a) const {
        const double x = (port_rad_.front() - a) * buckets_per_rad_; // NaN: bucket 0, stepped to beam 0
        int i = bucket_beam_[x > 0 ? size_t(std::min(x, double(bucket_beam_.size() - 1))) : 0];
        while (i > 0 && !(stbd_rad_[size_t(i) - 1] > a)) --i;
        while (i < beams - 1 && stbd_rad_[size_t(i)] > a) ++i;
        return i;
    }

    const BeamTable* table_ = nullptr;
    std::vector<double> centre_rad_, port_rad_, stbd_rad_; ///< the table's angles [rad]
    /// The table's fan cut into equal buckets from its port edge: the beam of each bucket's port end.
    std::vector<int> bucket_beam_;
    double buckets_per_rad_ = 0; ///< [1/rad]
    double narrowest_rad_ = 0, widest_rad_ = 0;
};

/// The grid of a sonar, shared: every caller asking for the same sonar geometry gets the same object (built
/// by the first). Throws InputError as the constructor does.
std::shared_ptr<const SonarGrid> sonar_grid(const SonarParams& sonar);

/// The error for a `sonar.beam_table` that does not fit the sonar (unknown name, another beam count), or
/// an empty string when it fits. `file` names where the value came from.
std::string beam_table_problem(const SonarParams& sonar);

} // namespace sonarsim

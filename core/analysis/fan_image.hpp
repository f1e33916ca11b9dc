// A fan-shaped sonar image (a PNG as a device's software or `sonarsim render` shows it) sampled back onto a
// polar grid of range bins x beams, so that `sonarsim compare` can measure it like an .aris frame or an .npy.
#pragma once
#include "core/data/polar_image.hpp"

#include <string>
#include <vector>

namespace sonarsim {

/// Where a fan image's samples are and what its gray levels mean. The fan points up: the apex at
/// (apex_x_px, apex_y_px) in pixel coordinates (x right, y down, pixel i covering [i, i + 1)), range r at
/// azimuth a (positive: port, on the left) at x = apex_x - r sin(a) px_per_m, y = apex_y - r cos(a) px_per_m.
/// Gray g stands for lo_db + g / 255 (hi_db - lo_db); gray 0 for the floor (nothing above lo_db).
struct FanGeometry {
    double apex_x_px = 0, apex_y_px = 0, px_per_m = 0;
    double azimuth_fov_deg = 0, range_min_m = 0, range_max_m = 0;
    double lo_db = 0, hi_db = 0;
    int beams = 0, bins = 0; ///< the polar grid the fan is sampled onto
    /// The beams' table (render's metadata names it; a table's fan need not be symmetric), or "uniform": the
    /// beams evenly over azimuth_fov_deg.
    std::string beam_table = "uniform";
};

/// "apex_x_px,apex_y_px,px_per_m,azimuth_fov_deg,range_min_m,range_max_m,lo_db,hi_db,beams,bins"; throws
/// InputError(origin, key, ...) naming the field that is missing or out of range.
FanGeometry parse_fan_geometry(const std::string& spec, const std::string& origin, const std::string& key);

/// The geometry of a fan PNG that `sonarsim render` wrote, from the metadata it wrote beside it (PREFIX.json
/// for PREFIX.png): its sonar, its display range, its sector layout at the PNG's height. Throws InputError
/// when there is no such file or its colour map is not gray (a colour map cannot be read back as levels).
FanGeometry fan_geometry_from_metadata(const std::string& png_path, int png_height_px);

/// The polar level image [dB] of the fan PNG at `path` (gray, or RGB with R = G = B): each (bin, beam)
/// centre sampled bilinearly; gray 0 is -inf. An empty `spec` takes the geometry from the metadata beside
/// the file. Throws InputError naming the file for an unreadable or non-gray PNG, or a fan outside it.
PolarImage load_fan_png(const std::string& path, const std::string& spec);

} // namespace sonarsim

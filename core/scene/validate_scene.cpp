// Cross-field checks of a whole scene: the range window, the sampler's combinations and ray budget, image
// and fan sizes, the elevation pattern's extent, the water surface above the sonar and the floor, display
// and export ranges.
#include "core/scene/params.hpp"
#include "core/scene/sampling_scheme.hpp"

#include "core/base/errors.hpp"
#include "core/data/pose.hpp"
#include "core/grid/beam_tables.hpp"
#include "core/grid/sonar_grid.hpp"
#include "core/grid/sensor_patterns.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace sonarsim {

void validate_scene(const SceneDesc& s, const std::string& file, const std::vector<std::string>& just_set) {
    // Whether `b`, not `a`, is the key to name: the caller has just set b and not a.
    auto second = [&](const char* a, const char* b) {
        auto set = [&](const char* k) {
            return std::find(just_set.begin(), just_set.end(), k) != just_set.end();
        };
        return set(b) && !set(a);
    };
    // "KEY (value) must be below OTHER (value)", said of the key the caller set.
    auto order = [&](const char* lo_key, double lo, const char* hi_key, double hi) {
        auto name = [](const char* k) { return std::string(std::strrchr(k, '.') + 1); };
        if (second(lo_key, hi_key))
            throw InputError(file, hi_key,
                             name(hi_key) + " (" + number_text(hi) + ") must be above " + name(lo_key) +
                                 " (" + number_text(lo) + ")");
        throw InputError(file, lo_key,
                         name(lo_key) + " (" + number_text(lo) + ") must be below " + name(hi_key) + " (" +
                             number_text(hi) + ")");
    };
    static const SceneDesc defaults;
    for (auto& p : scene_params())
        if (!p.used_by(s.sonar.kind) && p.get(s) != p.get(defaults)) {
            std::string users;
            for (SonarKind k : {SonarKind::Imaging, SonarKind::Sidescan, SonarKind::Scanning})
                if (p.used_by(k)) users += (users.empty() ? "" : " or ") + kind_name(k);
            throw InputError(file, p.key,
                             "not used by sonar.kind \"" + kind_name(s.sonar.kind) +
                                 "\"; allowed: leave it out, "
                                 "or sonar.kind " +
                                 users);
        }
    if (const std::string problem = beam_table_problem(s.sonar); !problem.empty())
        throw InputError(file, "sonar.beam_table", problem);
    if (const BeamTable* t = find_beam_table(s.sonar.beam_table)) { // the table's fan, not another
        const double span = t->port_edge_deg.front() - t->starboard_edge_deg.back();
        if (!(std::abs(s.sonar.azimuth_fov_deg - span) <= 0.01 * span))
            throw InputError(file, "sonar.azimuth_fov_deg",
                             "value " + number_text(s.sonar.azimuth_fov_deg) +
                                 " deg is not the fan of beam table " + t->name + " (" + number_text(span) +
                                 " deg); allowed: within 1 % of it, or another "
                                 "field of view with sonar.beam_table \"uniform\"");
    }
    if (!(s.sonar.range_min_m < s.sonar.range_max_m))
        order("sonar.range_min_m", s.sonar.range_min_m, "sonar.range_max_m", s.sonar.range_max_m);
    if (s.sonar.beams % s.sonar.pings_per_frame != 0)
        throw InputError(file, "sonar.pings_per_frame",
                         "value " + std::to_string(s.sonar.pings_per_frame) +
                             " does not divide sonar.beams (" + std::to_string(s.sonar.beams) +
                             "): each ping fires every P-th beam");
    const PlacementSpec& placement = placement_spec(s.sampling.placement);
    if (placement.binning_reason && s.sampling.binning == EchoBinning::Point)
        throw InputError(file, "sampling.binning",
                         std::string(placement.name) + " placement needs \"footprint\" binning (" +
                             placement.binning_reason +
                             "): use sampling.placement \"grid\" with \"point\" binning (sampling.scheme "
                             "\"uniform\")");
    if (s.sampling.normals == NormalSource::Paper && !placement.regular_grid)
        throw InputError(file, "sampling.normals",
                         "\"paper\" normals need the regular ray grid: use sampling.scheme \"uniform\" or "
                         "\"spread\" with them");
    const double rays = double(s.sonar.beams) * s.sampling.azimuth_rays * s.sampling.elevation_rays *
                        (s.sampling.placement == RayPlacement::Jittered ? 4 : 1);
    if (rays > kMaxRaysPerImage)
        throw InputError(
            file, "sampling.elevation_rays",
            std::string(s.sampling.placement == RayPlacement::Jittered ? "4 (jittered) x " : "") +
                "beams x azimuth_rays x elevation_rays = " + number_text(rays) + " exceeds the limit of " +
                number_text(kMaxRaysPerImage) + " rays per image");
    // Ranges are carried in single precision; a bin narrower than 1 um resolves nothing.
    const double bin_m = range_bin_m(s.sonar);
    if (!(bin_m >= kMinRangeBinM))
        throw InputError(file, "sonar.range_bins",
                         "range bins of " + number_text(bin_m) +
                             " m ((range_max_m - range_min_m) / range_bins) are below " + "the minimum of " +
                             number_text(kMinRangeBinM) + " m; use fewer bins or a wider window");
    const double cells = double(s.sonar.range_bins) * s.sonar.beams;
    if (cells > kMaxImageCells)
        throw InputError(file, "sonar.range_bins",
                         "range_bins x beams = " + number_text(cells) + " exceeds the limit of " +
                             number_text(kMaxImageCells) + " cells per image");
    const double sector_px = sector_image_pixels(s.sonar);
    if (!(sector_px <= kMaxImageCells))
        throw InputError(file,
                         second("sonar.range_min_m", "sonar.range_max_m") ? "sonar.range_max_m"
                                                                          : "sonar.range_min_m",
                         "the sector image would have " + number_text(sector_px) + " pixels (limit " +
                             number_text(kMaxImageCells) +
                             "): range_min_m is too close to range_max_m for this field of view");
    if (s.sensor.range_resolution_m > range_window_m(s.sonar) / 4)
        throw InputError(file, "sensor.range_resolution_m",
                         "value " + number_text(s.sensor.range_resolution_m) +
                             " m is coarser than a quarter of the range window; allowed: [0, " +
                             number_text(range_window_m(s.sonar) / 4) + "] m");
    if (const auto& h = s.water.surface_height_m) {
        if (!(s.sonar.pose.position_m[2] < *h))
            throw InputError(file, "water.surface_height_m",
                             "the sonar (z = " + number_text(s.sonar.pose.position_m[2]) +
                                 " m) must be below the water surface (z = " + number_text(*h) + " m)");
        if (s.seafloor && !(s.seafloor->height_m < *h))
            throw InputError(file, "water.surface_height_m",
                             "the seafloor (z = " + number_text(s.seafloor->height_m) +
                                 " m) must be below the water surface (z = " + number_text(*h) + " m)");
    }
    if (!(s.display.lo_db < s.display.hi_db))
        order("display.lo_db", s.display.lo_db, "display.hi_db", s.display.hi_db);
    if (!s.exports.auto_range && !(s.exports.lo_db < s.exports.hi_db))
        order("export.lo_db", s.exports.lo_db, "export.hi_db", s.exports.hi_db);
    for (size_t i = 0; i < s.objects.size(); ++i) {
        const auto& o = s.objects[i];
        for (double c : o.scale)
            if (!(c > 0) || !std::isfinite(c))
                throw InputError(file, "objects[" + std::to_string(i) + "].scale",
                                 "scale must be finite and > 0");
    }
}

double sector_image_pixels(const SonarParams& s) {
    // The fan as the sonar's grid lays it out, in double precision (absurd windows give a large number).
    return SonarGrid(s).fan_pixels_unbounded();
}

} // namespace sonarsim

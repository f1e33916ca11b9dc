#include "core/grid/beam_tables.hpp"
#include "core/analysis/fan_image.hpp"

#include "core/base/errors.hpp"
#include "core/base/file_io.hpp"
#include "core/data/pose.hpp"
#include "core/display/image.hpp"
#include "core/grid/sonar_grid.hpp"
#include "core/scene/scene_io.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stb/stb_image.h>
#include <vector>

namespace sonarsim {

namespace {

constexpr const char* kFanFields[] = {"apex_x_px",   "apex_y_px",   "px_per_m", "azimuth_fov_deg",
                                      "range_min_m", "range_max_m", "lo_db",    "hi_db",
                                      "beams",       "bins"};

std::string fmt(double v) {
    std::ostringstream o;
    o << v;
    return o.str();
}

} // namespace

FanGeometry parse_fan_geometry(const std::string& spec, const std::string& origin, const std::string& key) {
    std::vector<double> v;
    std::stringstream in(spec);
    std::string item;
    while (std::getline(in, item, ',')) {
        char* end = nullptr;
        const double x = std::strtod(item.c_str(), &end);
        if (item.empty() || *end != '\0' || !std::isfinite(x))
            throw InputError(origin, key,
                             "\"" + item + "\" is not a finite number (field " +
                                 kFanFields[std::min<size_t>(v.size(), 9)] + ")");
        v.push_back(x);
    }
    std::string expected;
    for (const char* f : kFanFields) expected += (expected.empty() ? "" : ",") + std::string(f);
    if (v.size() != 10)
        throw InputError(origin, key,
                         "expected 10 numbers " + expected + "; got " + std::to_string(v.size()));
    FanGeometry g{v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], int(v[8]), int(v[9])};
    auto bad = [&](const char* field, const std::string& allowed) {
        throw InputError(origin, key, std::string(field) + " must be " + allowed);
    };
    if (!(g.px_per_m > 0)) bad("px_per_m", "above 0");
    if (!(g.azimuth_fov_deg > 0 && g.azimuth_fov_deg < 180)) bad("azimuth_fov_deg", "in (0, 180)");
    if (!(g.range_min_m >= 0 && g.range_min_m < g.range_max_m)) bad("range_min_m", "in [0, range_max_m)");
    if (!(g.lo_db < g.hi_db)) bad("lo_db", "below hi_db");
    if (v[8] != g.beams || g.beams < 1 || g.beams > 4096) bad("beams", "an integer in [1, 4096]");
    if (v[9] != g.bins || g.bins < 1 || g.bins > 65536) bad("bins", "an integer in [1, 65536]");
    return g;
}

FanGeometry fan_geometry_from_metadata(const std::string& png_path, int height) {
    const std::string meta = std::filesystem::path(png_path).replace_extension(".json").string();
    std::error_code ec;
    if (!std::filesystem::is_regular_file(meta, ec))
        throw InputError(
            png_path, "",
            "a fan PNG needs its geometry: the metadata `render` wrote beside it (" + meta +
                ", not found) or --fan-a/--fan-b " +
                "apex_x_px,apex_y_px,px_per_m,azimuth_fov_deg,range_min_m,range_max_m,lo_db,hi_db,"
                "beams,bins");
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(read_file_bytes(meta));
    } catch (const nlohmann::json::exception& e) {
        throw InputError(meta, "", std::string("not JSON: ") + e.what());
    }
    if (!j.contains("sonar") || !j.contains("display_range_db") || !j.contains("display"))
        throw InputError(meta, "",
                         "not the metadata of `sonarsim render` (no sonar, display or display_range_db)");
    if (j["display"].value("colormap", "gray") != "gray")
        throw InputError(meta, "display.colormap",
                         "the fan was drawn with the \"" + j["display"]["colormap"].get<std::string>() +
                             "\" colour map, which cannot be read back as levels; allowed: \"gray\" "
                             "(render with --set display.colormap=gray)");
    SonarParams s;
    const nlohmann::json& sj = j["sonar"];
    s.azimuth_fov_deg = sj.at("azimuth_fov_deg"), s.beams = sj.at("beams");
    s.range_min_m = sj.at("range_min_m"), s.range_max_m = sj.at("range_max_m"),
    s.range_bins = sj.at("range_bins");
    s.beam_table = sj.value("beam_table", std::string(kUniformBeams)); // a table's fan need not be symmetric
    const SectorLayout layout(s, height);
    FanGeometry g;
    layout.polar_to_pixel(0, 0, g.apex_x_px, g.apex_y_px);
    g.px_per_m = 1 / layout.metres_per_pixel();
    g.azimuth_fov_deg = s.azimuth_fov_deg, g.range_min_m = s.range_min_m, g.range_max_m = s.range_max_m;
    g.lo_db = j["display_range_db"].at(0), g.hi_db = j["display_range_db"].at(1);
    g.beams = s.beams, g.bins = s.range_bins;
    g.beam_table = s.beam_table;
    return g;
}

PolarImage load_fan_png(const std::string& path, const std::string& spec) {
    const std::string bytes = read_file_bytes(path);
    int w = 0, h = 0, channels = 0;
    std::unique_ptr<unsigned char, void (*)(void*)> px(
        stbi_load_from_memory(reinterpret_cast<const unsigned char*>(bytes.data()), int(bytes.size()), &w, &h,
                              &channels, 3),
        stbi_image_free);
    if (!px) throw InputError(path, "", std::string("not a readable PNG: ") + stbi_failure_reason());
    const FanGeometry g =
        spec.empty() ? fan_geometry_from_metadata(path, h) : parse_fan_geometry(spec, path, "fan");
    const unsigned char* rgb = px.get();
    // Pixels whose channels differ are counted: a few are the background at the fan's border (read as
    // nothing), many a colour map, which cannot be read back as levels.
    std::size_t coloured = 0, read = 0;
    auto gray = [&](int x, int y) {
        const unsigned char* p = rgb + 3 * (size_t(y) * size_t(w) + size_t(x));
        const bool colour = std::abs(int(p[0]) - int(p[1])) > 2 || std::abs(int(p[1]) - int(p[2])) > 2;
        coloured += colour, ++read;
        return colour ? 0.0 : double(p[1]); // the background around the fan: nothing
    };
    PolarImage out;
    out.bins = g.bins, out.beams = g.beams;
    out.level_db.resize(size_t(g.bins) * size_t(g.beams));
    SonarParams sonar; // the image's polar grid: its bins' and beams' centres
    sonar.beams = g.beams, sonar.range_bins = g.bins, sonar.azimuth_fov_deg = g.azimuth_fov_deg;
    sonar.range_min_m = g.range_min_m, sonar.range_max_m = g.range_max_m, sonar.beam_table = g.beam_table;
    const std::shared_ptr<const SonarGrid> grid = sonar_grid(sonar);
    for (int k = 0; k < g.bins; ++k)
        for (int i = 0; i < g.beams; ++i) {
            const double r = grid->bin_centre_m(k), a = deg2rad(grid->beam_azimuth_deg(i));
            // Continuous pixel coordinates, then the four pixel centres around them.
            const double x = g.apex_x_px - r * std::sin(a) * g.px_per_m - 0.5;
            const double y = g.apex_y_px - r * std::cos(a) * g.px_per_m - 0.5;
            if (x < -1 || y < -1 || x > w || y > h)
                throw InputError(path, "fan",
                                 "the fan reaches outside the " + std::to_string(w) + " x " +
                                     std::to_string(h) + " px image (range " + fmt(r) + " m, azimuth " +
                                     fmt(rad2deg(a)) + " deg at pixel " + fmt(x) + ", " + fmt(y) + ")");
            // Bilinear between the four pixel centres around (x, y); at the border the edge pixels repeat.
            const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
            const double fx = x - x0, fy = y - y0;
            auto at = [&](int xi, int yi) {
                return gray(std::clamp(xi, 0, w - 1), std::clamp(yi, 0, h - 1));
            };
            const double v = (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x0 + 1, y0)) +
                             fy * ((1 - fx) * at(x0, y0 + 1) + fx * at(x0 + 1, y0 + 1));
            out.level_db[size_t(k) * size_t(g.beams) + size_t(i)] =
                v < 0.5 ? -std::numeric_limits<float>::infinity()
                        : float(g.lo_db + v / 255 * (g.hi_db - g.lo_db));
        }
    if (coloured > read / 50)
        throw InputError(
            path, "",
            std::to_string(100 * coloured / read) +
                " % of the fan's pixels are not gray: a colour map cannot be read back as levels; "
                "allowed: gray fans (R = G = B)");
    return out;
}

} // namespace sonarsim

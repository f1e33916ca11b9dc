#include "core/io/ping_output.hpp"

#include "core/display/display_range.hpp"
#include "core/io/ground_truth_files.hpp"
#include "core/io/output.hpp"
#include "core/io/ping360_log.hpp"
#include "core/io/xtf.hpp"
#include "core/kinds/kind_images.hpp"
#include "core/scene/scene_io.hpp"
#include "core/sensor/sensor.hpp"
#include "core/shading/physics.hpp"

#include <algorithm>
#include <cmath>

namespace sonarsim {
namespace {

Bytes image_png(const SceneDesc& s, const PingSeries& p, const PingViews& v) {
    return encode_png(ping_image(s, p, v));
}

/// The raw arrays' shape: (pings, channels, bins), a scan's (steps, bins).
std::vector<std::size_t> raw_shape(const PingSeries& p) {
    std::vector<std::size_t> shape = {std::size_t(p.pings), std::size_t(p.channels), std::size_t(p.bins)};
    if (p.channels == 1) shape.erase(shape.begin() + 1);
    return shape;
}
Bytes raw_npy(const std::vector<float>& levels, const PingSeries& p) {
    return encode_npy_array(levels.data(), levels.size() * 4, "<f4", raw_shape(p));
}
Bytes level_npy(const SceneDesc&, const PingSeries& p, const PingViews&) {
    return raw_npy(p.level_db, p);
}
Bytes ideal_npy(const SceneDesc&, const PingSeries& p, const PingViews&) {
    return raw_npy(p.ideal_db, p);
}
Bytes waterfall_npy(const SceneDesc&, const PingSeries&, const PingViews& v) {
    return encode_npy(v.shown); // a side-scan's shown levels are its waterfall
}
Bytes metadata_json(const SceneDesc& s, const PingSeries& p, const PingViews& v) {
    return to_bytes(ping_metadata(s, p, v).dump(2) + "\n");
}
Bytes xtf_file(const SceneDesc& s, const PingSeries& p, const PingViews& v) {
    return encode_xtf(s, p, v.mapping);
}
Bytes ping360_file(const SceneDesc& s, const PingSeries& p, const PingViews& v) {
    return encode_ping360_log(s, p, v.mapping, s.source_file);
}
bool ping360_log(const SceneDesc& s) {
    return s.sonar.kind == SonarKind::Scanning && ping360_log_problem(s).empty();
}
bool sidescan(const SceneDesc& s) {
    return s.sonar.kind == SonarKind::Sidescan;
}
bool sensor_applied(const SceneDesc& s) {
    return !sensor_is_ideal(s);
}

json number_or_null(double v) {
    return std::isfinite(v) ? json(v) : json(nullptr);
}

} // namespace

const std::vector<PingOutput>& ping_outputs() {
    static const std::vector<PingOutput> table = {
        {".png",
         "the waterfall (side-scan: port | starboard, newest ping at the top) or the sweep (scanning)",
         image_png},
        {".npy", "levels dB through the sensor, float32 (pings, channels, bins); scanning (steps, bins)",
         level_npy},
        {"_waterfall.npy",
         "the waterfall's levels dB as shown (pings, 2 x bins: port far..near, starboard "
         "near..far; slant or ground range)",
         waterfall_npy, sidescan},
        {".xtf",
         "the side-scan's pings as XTF (eXtended Triton Format): port and starboard, one byte a sample",
         xtf_file, sidescan, SonarKind::Sidescan},
        {"_ping360.bin", "the sweep as a Ping Viewer sensor log (Ping360 device_data messages)", ping360_file,
         ping360_log, SonarKind::Scanning},
        {"_ideal.npy", "L_EN dB before the sensor stage, as .npy (only when the sensor is not ideal)",
         ideal_npy, sensor_applied},
        {".json", "metadata: parameters and each ping's time, pose, head angle, first bottom return",
         metadata_json}};
    return table;
}

ByteMapping ping_byte_mapping(const SceneDesc& s, const PingSeries& p) {
    return choose_byte_mapping(s.exports, size_t(p.pings), [&](size_t i) {
        PolarImage img;
        img.bins = p.bins, img.beams = p.channels;
        img.level_db.resize(size_t(p.bins) * size_t(p.channels));
        for (int ch = 0; ch < p.channels; ++ch)
            for (int k = 0; k < p.bins; ++k)
                img.level_db[size_t(k) * size_t(p.channels) + size_t(ch)] = p.profile(int(i), ch)[k];
        return img;
    });
}

std::string ping_outputs_text(const std::string& prefix, const SceneDesc& scene) {
    std::string text;
    for (auto& o : ping_outputs())
        if (!o.wanted || o.wanted(scene))
            text += (text.empty() ? "" : ", ") + prefix + o.suffix + " (" + o.what + ")";
    return text;
}

std::vector<std::string> write_ping_files(const std::string& prefix, const SceneDesc& scene,
                                          const PingSeries& series,
                                          std::vector<std::pair<std::string, Bytes>> extra) {
    const PingViews views = ping_views(scene, series);
    std::vector<std::pair<std::string, Bytes>> files;
    for (auto& o : ping_outputs())
        if (!o.wanted || o.wanted(scene))
            files.emplace_back(prefix + o.suffix, o.encode(scene, series, views));
    for (auto& f : ping_ground_truth_files(prefix, series)) files.push_back(std::move(f));
    for (auto& f : extra) files.push_back(std::move(f));
    write_files_atomically(files);
    std::vector<std::string> paths;
    for (auto& f : files) paths.push_back(f.first);
    return paths;
}

std::vector<std::pair<std::string, Bytes>> ping_ground_truth_files(const std::string& prefix,
                                                                   const PingSeries& series) {
    if (series.truth.empty()) return {};
    return ground_truth_files(prefix, series.truth, raw_shape(series));
}

PingViews ping_views(const SceneDesc& s, const PingSeries& p) {
    PingViews v;
    v.shown = s.sonar.kind == SonarKind::Sidescan ? waterfall_levels(p, s.sidescan.range, s.sonar.range_max_m)
                                                  : scan_levels(p);
    v.display = effective_display(v.shown, s.display);
    v.mapping = ping_byte_mapping(s, p);
    return v;
}

Image8 ping_image(const SceneDesc& s, const PingSeries& p, const PingViews& v) {
    if (s.sonar.kind == SonarKind::Sidescan) return waterfall_image(v.shown, v.display);
    return sweep_image(p, v.display, s.sonar.range_max_m, std::clamp(2 * p.bins, 256, 1024));
}

json ping_metadata(const SceneDesc& s, const PingSeries& p, const PingViews& v) {
    json j = scene_to_json(s);
    const double c = sound_speed_m_s(s.water.temperature_c, s.water.depth_m);
    j["sound_speed_m_s"] = c;
    j["alpha_db_per_m"] = absorption_db_per_m(s.sonar.frequency_khz, s.water.temperature_c, s.water.depth_m);
    j["ping_interval_s"] = p.ping_interval_s;
    j["ping_interval_rule"] = "2 r_max / c + the kind's overhead (" +
                              std::string(s.sonar.kind == SonarKind::Sidescan ? "sidescan.ping_overhead_ms"
                                                                              : "scanning.step_overhead_ms") +
                              ")";
    j["channels"] = json::array();
    for (int ch = 0; ch < p.channels; ++ch) j["channels"].push_back(channel_name(s.sonar.kind, ch));
    j["range_bin_edges_m"] = p.grid->bin_edges_m();
    j["display_used"] = {{"lo_db", v.display.lo_db}, {"hi_db", v.display.hi_db}};
    json pings = json::array();
    for (int i = 0; i < p.pings; ++i) {
        const Ping& g = p.schedule[size_t(i)];
        json e = {{"time_s", g.time_s},
                  {"position_m", g.vehicle.position_m},
                  {"orientation_deg", g.vehicle.orientation_deg}};
        if (s.sonar.kind == SonarKind::Scanning) e["head_deg"] = g.head_deg;
        if (s.sonar.kind == SonarKind::Sidescan)
            e["first_return_m"] = number_or_null(p.first_return_m[size_t(i)]);
        pings.push_back(e);
    }
    j["pings"] = pings;
    // The 8-bit files' mapping (.xtf, _ping360.bin), and why a scan has no Ping360 log.
    j["byte_mapping"] = {
        {"lo_db", v.mapping.lo_db}, {"hi_db", v.mapping.hi_db}, {"automatic", v.mapping.automatic}};
    if (const std::string problem = ping360_log_problem(s);
        s.sonar.kind == SonarKind::Scanning && !problem.empty())
        j["ping360_log"] = "not written: " + problem;
    j["rays_traced"] = p.rays_traced;
    j["profiles"] = {{"traced", p.traced_profiles},
                     {"shaded_from_earlier_hits", p.shaded_profiles},
                     {"copied", p.copied_profiles}};
    j["render_ms"] = p.trace_ms;
    j["stage_ms"] = {{"trace", p.stage_ms[0]},
                     {"shade", p.stage_ms[1]},
                     {"sensor", p.stage_ms[2]},
                     {"image", p.stage_ms[3]}};
    return j;
}

} // namespace sonarsim

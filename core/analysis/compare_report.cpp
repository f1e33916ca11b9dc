#include "core/analysis/compare_report.hpp"

#include "core/base/errors.hpp"
#include "core/base/file_io.hpp"
#include "core/analysis/fan_image.hpp"
#include "core/io/aris_read.hpp"
#include "core/io/output.hpp"

#include <cmath>
#include <filesystem>

namespace sonarsim {
namespace {

nlohmann::json number(double x) {
    return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr);
}

template <typename V> nlohmann::json numbers(const V& v) {
    nlohmann::json a = nlohmann::json::array();
    for (double x : v) a.push_back(number(x));
    return a;
}

nlohmann::json stats_json(const ImageStats& s) {
    nlohmann::json j;
    j["bins"] = s.bins, j["beams"] = s.beams;
    j["floor_fraction"] = number(s.floor_fraction);
    j["mean_level_db"] = number(s.mean_level_db);
    j["range_profile_db"] = numbers(s.range_profile_db);
    j["contrast_intensity"] = number(s.contrast_intensity);
    j["contrast_amplitude"] = number(s.contrast_amplitude);
    j["quantiles"] = numbers(kCompareQuantiles);
    j["quantiles_db"] = numbers(s.quantiles_db);
    j["grain_range"] = numbers(s.grain_range);
    j["grain_beams"] = numbers(s.grain_beams);
    j["histogram"] = numbers(s.histogram);
    j["samples_used"] = s.samples_used;
    return j;
}

} // namespace

PolarImage load_compare_image(const std::string& path, std::size_t frame, const std::string& fan) {
    const std::string ext = std::filesystem::path(path).extension().string();
    if (!fan.empty() && ext != ".png")
        throw InputError(path, "fan", "a fan geometry is for .png images only");
    if (ext == ".aris") return read_aris_frame(path, frame).level_db;
    if (ext == ".png") {
        if (frame != 0) throw InputError(path, "frame", "a PNG holds one frame; allowed: 0");
        return load_fan_png(path, fan);
    }
    if (ext == ".npy") {
        if (frame != 0) throw InputError(path, "frame", "an .npy image holds one frame; allowed: 0");
        const std::string text = read_file_bytes(path);
        return decode_npy(Bytes(text.begin(), text.end()), path);
    }
    throw InputError(path, "",
                     "unknown image file \"" + ext +
                         "\"; allowed: .aris (a recording), .npy (a level "
                         "image as render writes it), .png (a gray fan image)");
}

nlohmann::json compare_report(const ImageStats& a, const ImageStats& b, const PairStats& p) {
    nlohmann::json j;
    j["a"] = stats_json(a), j["b"] = stats_json(b);
    nlohmann::json& q = j["pair"];
    q["profile_rms_db"] = number(p.profile_rms_db);
    q["histogram_distance"] = number(p.histogram_distance);
    q["contrast_difference"] = number(p.contrast_difference);
    q["aligned"] = p.aligned;
    if (p.aligned) {
        q["correlation"] = number(p.correlation);
        q["highlight_overlap"] = number(p.highlight_overlap);
        q["shadow_overlap"] = number(p.shadow_overlap);
    }
    return j;
}

nlohmann::json compare_images_report(const PolarImage& a, const PolarImage& b, const CompareOptions& o) {
    const ImageStats sa = image_stats(a, o), sb = image_stats(b, o);
    nlohmann::json j = compare_report(sa, sb, compare_stats(a, sa, b, sb, o));
    j["options"] = {{"local_half_window", o.local_half_window},
                    {"profile_slices", o.profile_slices},
                    {"max_lag", o.max_lag},
                    {"histogram_lo_db", o.histogram_lo_db},
                    {"histogram_hi_db", o.histogram_hi_db},
                    {"histogram_step_db", o.histogram_step_db}};
    return j;
}

} // namespace sonarsim

#include "core/io/byte_mapping.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace sonarsim {
namespace {

/// Levels in 1/100 dB bins over [kLowestDb, -kLowestDb); levels outside count in the end bins.
constexpr double kBinDb = 0.01, kLowestDb = -1000;
constexpr std::size_t kBins = std::size_t(-2 * kLowestDb / kBinDb);

std::string percent(double fraction) {
    char b[32];
    std::snprintf(b, sizeof b, "%.2f %%", 100 * fraction);
    return b;
}

std::string db(double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.1f", v);
    return b;
}

nlohmann::json clip_json(const ClipCount& c) {
    return {{"samples", c.samples},
            {"with_level", c.with_level},
            {"at_255", c.high},
            {"at_0_with_level", c.low},
            {"at_255_fraction", c.high_fraction()},
            {"at_0_with_level_fraction", c.low_fraction()}};
}

} // namespace

std::uint8_t level_byte(float level_db, const ByteMapping& m) {
    if (!(level_db > -INFINITY)) return 0; // nothing echoes (and NaN)
    const double t = (double(level_db) - m.lo_db) / (m.hi_db - m.lo_db);
    return std::uint8_t(std::lround(255.0 * std::clamp(t, 0.0, 1.0)));
}

ClipCount& ClipCount::operator+=(const ClipCount& o) {
    samples += o.samples, with_level += o.with_level, high += o.high, low += o.low;
    return *this;
}

std::vector<std::uint8_t> image_bytes(const PolarImage& img, const ByteMapping& m, ClipCount& count) {
    std::vector<std::uint8_t> out(img.level_db.size());
    for (std::size_t i = 0; i < out.size(); ++i) {
        const float l = img.level_db[i];
        const std::uint8_t b = level_byte(l, m);
        const bool level = std::isfinite(l);
        count.with_level += level;
        count.high += b == 255;
        count.low += level && b == 0;
        out[i] = b;
    }
    count.samples += out.size();
    return out;
}

ByteMapping choose_byte_mapping(const ExportParams& p, std::size_t frames, const FrameImageSource& image) {
    ByteMapping m{p.lo_db, p.hi_db, false};
    if (!p.auto_range) return m;
    m.automatic = true;
    std::vector<std::uint64_t> hist(kBins, 0);
    std::uint64_t total = 0;
    for (std::size_t k = 0; k < frames; ++k)
        for (float v : image(k).level_db)
            if (std::isfinite(v)) {
                const double bin = std::floor((double(v) - kLowestDb) / kBinDb);
                ++hist[std::size_t(std::clamp(bin, 0.0, double(kBins - 1)))];
                ++total;
            }
    if (total == 0) return m;
    // The smallest bin edge with at least the quantile's share of the levels below it.
    const auto want = std::uint64_t(std::ceil(kAutoExportHighQuantile * double(total)));
    std::uint64_t below = 0;
    std::size_t i = 0;
    while (i < kBins && below + hist[i] < want) below += hist[i++];
    const double edge = kLowestDb + double(i + 1) * kBinDb;
    m.hi_db = std::ceil(edge * 10 - 1e-9) / 10;                    // rounded up to 0.1 dB
    m.lo_db = std::round((m.hi_db - kAutoExportSpanDb) * 10) / 10; // 31.1, not 31.099999999999994
    return m;
}

nlohmann::json ExportReport::to_json(const std::string& file) const {
    nlohmann::json frames_json = nlohmann::json::array();
    for (std::size_t k = 0; k < frames.size(); ++k) {
        auto f = clip_json(frames[k]);
        f["frame"] = k;
        frames_json.push_back(f);
    }
    nlohmann::json j = {
        {"file", file},
        {"byte_mapping",
         {{"lo_db", mapping.lo_db},
          {"hi_db", mapping.hi_db},
          {"chosen_by", mapping.automatic ? "export.auto" : "export.lo_db, export.hi_db"},
          {"rule", mapping.automatic
                       ? "hi_db: the 99.5th percentile of all frames' finite levels, rounded up to 0.1 "
                         "dB; lo_db = hi_db - 80 (a byte is 80/255 dB, as ARIS reads it)"
                       : "as given"},
          {"byte", "round(255 clamp((L - lo_db) / (hi_db - lo_db), 0, 1)); 0 where nothing echoes"},
          {"level", "L: the frame's .npy, the image level dB"}}},
        {"clipped", clip_json(total)},
        {"frames", frames_json}};
    if (!notes.empty()) j["notes"] = notes;
    return j;
}

std::string ExportReport::warning(const std::string& file) const {
    if (total.high_fraction() <= kClipWarningFraction && total.low_fraction() <= kClipWarningFraction)
        return "";
    const std::string mapping_text = mapping.automatic
                                         ? "export.auto; export.auto=false with export.lo_db/hi_db widens it"
                                         : "export.lo_db/hi_db; export.auto=true chooses them from the data";
    return file + ": " + percent(total.high_fraction()) + " of the samples are clipped at 255 and " +
           percent(total.low_fraction()) +
           " have a level (echo or noise) below byte 1 and are written as 0 " +
           "(bytes 0-255 = " + db(mapping.lo_db) + "-" + db(mapping.hi_db) + " dB, " + mapping_text +
           "); per frame in " + file + ".json";
}

std::string ExportReport::summary() const {
    return "bytes 0-255 = " + db(mapping.lo_db) + "-" + db(mapping.hi_db) + " dB (" +
           (mapping.automatic ? "export.auto" : "export.lo_db, export.hi_db") + "), " +
           percent(total.high_fraction()) + " of samples at 255, " + percent(total.low_fraction()) +
           " with a level at 0";
}

} // namespace sonarsim

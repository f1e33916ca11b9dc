// `sonarsim compare`'s inputs and report: an image from an .aris frame or a level .npy, and the statistics of
// two images as JSON (what the command writes and the Python module returns).
#pragma once
#include "core/analysis/compare.hpp"

#include <nlohmann/json.hpp>
#include <string>

namespace sonarsim {

/// The level image [dB] in `path`: frame `frame` of an .aris recording (its bytes as dB above the device's
/// floor), an .npy level image as `render` writes it (range bins x beams, float32), or a gray fan PNG
/// sampled back onto its polar grid (analysis/fan_image.hpp; `fan`: its geometry, empty: from the metadata
/// `render` wrote beside it). Throws InputError naming the file (an unknown extension: the allowed ones).
PolarImage load_compare_image(const std::string& path, std::size_t frame, const std::string& fan = "");

/// {"a": stats, "b": stats, "pair": ...}; non-finite numbers are written as null.
nlohmann::json compare_report(const ImageStats& a, const ImageStats& b, const PairStats& pair);

/// Both images' statistics and the pair's, as compare_report.
nlohmann::json compare_images_report(const PolarImage& a, const PolarImage& b, const CompareOptions& o = {});

} // namespace sonarsim

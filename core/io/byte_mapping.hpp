// The 8-bit exports' mapping of image levels to bytes (.aris, MCAP uint8): chosen from the exported frames
// (export.auto) or given (export.lo_db, export.hi_db), one mapping for every frame of a file, and the count
// of the samples it clips, per frame and for the file.
#pragma once
#include "core/data/polar_image.hpp"
#include "core/data/scene.hpp"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace sonarsim {

/// byte = 255 clamp((L - lo_db) / (hi_db - lo_db), 0, 1), rounded; 0 where nothing echoes (L = -inf).
struct ByteMapping {
    double lo_db = 0, hi_db = 80;
    bool automatic = false; ///< chosen from the frames' levels (export.auto)
};

/// The span of the automatic mapping [dB]: ARIS's own reading of a byte is dB = byte 80/255 (SENSORS.md
/// 2.6), so a vendor tool reads level differences right; only the offset (the gain) is chosen.
constexpr double kAutoExportSpanDb = 80;
/// The automatic mapping puts byte 255 at this quantile of the frames' finite levels (as display.auto).
constexpr double kAutoExportHighQuantile = 0.995;
/// Clipping beyond this fraction of a file's samples (at 0 or at 255) is said on stderr.
constexpr double kClipWarningFraction = 0.02;

/// The byte of image level `level_db`.
std::uint8_t level_byte(float level_db, const ByteMapping& mapping);

/// Samples a mapping clipped: written as 255, or written as 0 although they have a level (echo or noise;
/// where nothing echoes, L = -inf, 0 is the right byte).
struct ClipCount {
    std::size_t samples = 0;    ///< all samples
    std::size_t with_level = 0; ///< with a finite level
    std::size_t high = 0;       ///< written as 255
    std::size_t low = 0;        ///< with a finite level, written as 0
    double high_fraction() const { return samples ? double(high) / double(samples) : 0; }
    double low_fraction() const { return samples ? double(low) / double(samples) : 0; }
    ClipCount& operator+=(const ClipCount& o);
};

/// The bytes of `image` in its own order (row-major: range bin, then beam), counted into `count`.
std::vector<std::uint8_t> image_bytes(const PolarImage& image, const ByteMapping& mapping, ClipCount& count);

/// L_EN image of frame k (range bins x beams, row 0 nearest, column 0 port-most), read one at a time.
using FrameImageSource = std::function<PolarImage(std::size_t k)>;

/// The mapping of a file of `frames` frames: export.lo_db/hi_db, or with export.auto the high quantile of
/// all frames' finite levels (read once each, a histogram of 1/100 dB bins) rounded up to 0.1 dB, and
/// kAutoExportSpanDb below. Frames with no echo at all keep lo_db/hi_db.
ByteMapping choose_byte_mapping(const ExportParams& params, std::size_t frames,
                                const FrameImageSource& image);

/// What an 8-bit export wrote: its mapping and what it clipped, per frame and in all.
struct ExportReport {
    ByteMapping mapping;
    std::vector<ClipCount> frames;
    ClipCount total;
    /// What the writer chose that the scene did not ask for (the nearest setting the format allows).
    std::vector<std::string> notes;
    /// {"byte_mapping": {...}, "clipped": {...}, "frames": [...]} and "notes" when there are any: the file's
    /// sidecar metadata.
    nlohmann::json to_json(const std::string& file) const;
    /// One line about what was clipped when it exceeds kClipWarningFraction, else "".
    std::string warning(const std::string& file) const;
    /// "bytes 0-255 = 31.9-111.9 dB (export.auto); 0.19 % of samples at 255, 0.01 % with a level at 0".
    std::string summary() const;
};

} // namespace sonarsim

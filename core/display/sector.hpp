// Display: gray mapping of L_EN, colour maps, and the sector-formed (fan) image with its pixel <-> (r, a)
// map.
#pragma once
#include "core/scene/scene.hpp"
#include "core/shading/shade.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace sonarsim {

struct Image8 {
    int width = 0, height = 0, channels = 0;
    std::vector<std::uint8_t> pixels; ///< row-major, top row first
};

/// gray = 255 clamp((L_EN - lo) / (hi - lo), 0, 1); -inf maps to 0. Returned as a float in [0, 255].
float gray_level(float level_db, double lo_db, double hi_db);

/// The display range an image is shown with: `display` itself, or with display.auto its lo/hi replaced by
/// the 5th and 99.5th percentiles of the image's finite levels as the fan shows them (each sample weighted
/// by its range, as the fan's area is; a histogram of 4096 bins, interpolated), at most kAutoDisplaySpanDb
/// and at least 1 dB apart. An image with no finite level keeps lo_db and hi_db.
DisplayParams effective_display(const PolarImage& img, const DisplayParams& display,
                                const SonarParams& sonar);

/// Widest automatic display range [dB]: a scene whose echoes stand 100 dB above its noise still shows the
/// texture of its echoes (speckle spans about 20 dB).
constexpr double kAutoDisplaySpanDb = 50;

/// RGB of a colour map at t in [0, 1].
std::array<std::uint8_t, 3> colormap_rgb(Colormap map, double t);
/// The colour a viewer shows for cells where nothing echoes (L_EN = -inf), distinct from the map's low end.
std::array<std::uint8_t, 3> no_echo_rgb(Colormap map);

/// The raw image as gray: range grows upward (row 0 of the data at the bottom), beam 0 (port) on the left.
Image8 polar_gray_image(const PolarImage& img, const DisplayParams& display);

/// Geometry of the sector-formed image: apex at the bottom centre, range up, port (positive azimuth) left.
class SectorLayout {
  public:
    SectorLayout(const SonarParams& sonar, int height_px);
    int width() const { return width_; }
    int height() const { return height_; }
    double metres_per_pixel() const { return m_per_px_; }
    /// Pixel centre (px + 0.5, py + 0.5) -> range [m], azimuth [deg]; false outside the fan.
    bool pixel_to_polar(double px, double py, double& range_m, double& azimuth_deg) const;
    /// Range and azimuth -> continuous pixel coordinates.
    void polar_to_pixel(double range_m, double azimuth_deg, double& px, double& py) const;
    /// Fractional (bin, beam) of a range and azimuth, in data index units (centres at integers).
    void polar_to_index(double range_m, double azimuth_deg, double& bin, double& beam) const;

  private:
    SonarParams s_;
    int width_ = 0, height_ = 0;
    double m_per_px_ = 0, y0_m_ = 0;
};

/// Default height of the sector image [px]: the number of range bins, kept within [256, 2048] (one pixel row
/// per bin up to 2048 bins), and lowered where needed so that the width stays within kMaxSectorWidth. A
/// 130 deg fan is about 1.8x as wide as high: 512 beams x 1500 bins give 2729 x 1500 px, where the beams at
/// r_max are 5 px apart.
int default_sector_height(const SonarParams& sonar);

/// Widest default sector image [px]: a texture width every OpenGL implementation takes.
constexpr int kMaxSectorWidth = 4096;

/// Precomputed pixel -> (bin, beam) bilinear weights of a sector layout: forming an image is then a gather,
/// parallel over rows (TBB), that visits only the pixels inside the fan. Building it is parallel too.
class SectorResampler {
  public:
    SectorResampler(const SonarParams& sonar, int height_px);
    /// True when it was built for the same image geometry.
    bool matches(const SonarParams& sonar, int height_px) const;
    /// The RGB fan: per pixel inside it, the bilinear interpolation in (bin, beam) of the gray levels
    /// (gray_level) of its four nearest samples, rounded, through the colour map; kFanBackground outside.
    /// The interpolation weights are kept to 1/kWeightOne (15 bits).
    /// Kernel::Portable forces the portable four-pixel loop (tests compare it with the default, which uses
    /// AVX2 gathers where the CPU has them; both give the same pixels).
    enum class Kernel { Best, Portable };
    Image8 apply(const PolarImage& img, const DisplayParams& display, Kernel kernel = Kernel::Best) const;
    const SectorLayout& layout() const { return layout_; }
    static constexpr int kWeightOne = 1 << 15;

  private:
    /// One pixel inside the fan. The gray levels are gathered from a copy of the image padded with one more
    /// bin and beam (repeating the last), so every tap reads the same four neighbours.
    struct Tap {
        std::int32_t index;   ///< bin * (beams + 1) + beam of the lower-left sample in the padded image
        std::uint16_t wb, wi; ///< weights of the next bin and of the next beam [1 / kWeightOne]
    };
    /// Consecutive pixels of one row inside the fan; their taps are at [first, first + x1 - x0).
    struct Run {
        std::int32_t x0, x1;
        std::uint32_t first;
    };
    SonarParams sonar_;
    int height_px_;
    SectorLayout layout_;
    // The taps, one array per field (apply reads four at a time).
    std::vector<std::int32_t> tap_index_;
    std::vector<std::uint16_t> tap_wb_, tap_wi_;
    std::vector<Run> runs_;
    std::vector<std::uint32_t> row_runs_; ///< runs of row y: runs_[row_runs_[y], row_runs_[y + 1])
};

/// The sector-formed image (RGB): bilinear in (bin, beam) of the gray levels, then the colour map.
Image8 sector_image(const PolarImage& img, const SonarParams& sonar, const DisplayParams& display,
                    int height_px = 0);

/// Background colour outside the fan.
constexpr std::array<std::uint8_t, 3> kFanBackground{24, 26, 32};

} // namespace sonarsim

// The sector-formed (fan) image: its pixel <-> (r, a) map over the sonar's grid (the grid lays the fan out)
// and the resampler that forms it.
#pragma once
#include "core/display/colormap.hpp"
#include "core/grid/sonar_grid.hpp"
#include "core/data/polar_image.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace sonarsim {

/// Geometry of the sector-formed image: apex at the bottom centre, range up, port (positive azimuth) left.
class SectorLayout {
  public:
    SectorLayout(std::shared_ptr<const SonarGrid> grid, int height_px);
    SectorLayout(const SonarParams& sonar, int height_px) : SectorLayout(sonar_grid(sonar), height_px) {}
    int width() const { return fan_.width_px; }
    int height() const { return fan_.height_px; }
    double metres_per_pixel() const { return fan_.m_per_px; }
    const SonarGrid& grid() const { return *grid_; }
    const std::shared_ptr<const SonarGrid>& grid_ptr() const { return grid_; }
    /// Pixel centre (px + 0.5, py + 0.5) -> range [m], azimuth [deg]; false outside the fan.
    bool pixel_to_polar(double px, double py, double& range_m, double& azimuth_deg) const;
    /// Range and azimuth -> continuous pixel coordinates.
    void polar_to_pixel(double range_m, double azimuth_deg, double& px, double& py) const;
    /// Fractional (bin, beam) of a range and azimuth, in data index units (centres at integers).
    void polar_to_index(double range_m, double azimuth_deg, double& bin, double& beam) const;

  private:
    std::shared_ptr<const SonarGrid> grid_;
    FanLayout fan_;
};

/// Default height of the sector image [px]: the number of range bins, kept within [256, 2048] (one pixel row
/// per bin up to 2048 bins), and lowered where needed so that the width stays within kMaxSectorWidth. A
/// 130 deg fan is about 1.8x as wide as high: 512 beams x 1500 bins give 2729 x 1500 px, where the beams at
/// r_max are 5 px apart.
inline int default_sector_height(const SonarParams& sonar) {
    return sonar_grid(sonar)->default_fan_height_px();
}

/// Widest default sector image [px]: a texture width every OpenGL implementation takes.
constexpr int kMaxSectorWidth = kMaxFanWidthPx;

/// Precomputed pixel -> (bin, beam) bilinear weights of a sector layout: forming an image is then a gather,
/// parallel over rows (TBB), that visits only the pixels inside the fan. Building it is parallel too.
class SectorResampler {
  public:
    /// height_px 0: the grid's default fan height.
    SectorResampler(std::shared_ptr<const SonarGrid> grid, int height_px);
    SectorResampler(const SonarParams& sonar, int height_px)
        : SectorResampler(sonar_grid(sonar), height_px) {}
    /// True when it was built for a grid of the same image geometry (another elevation aperture keeps it).
    bool matches(const SonarGrid& grid, int height_px) const {
        return height_px == height_px_ && (&grid == grid_.get() || grid.same_image(*grid_));
    }
    /// The RGB fan: per pixel inside it, the bilinear interpolation in (bin, beam) of the gray levels
    /// (gray_level) of its four nearest samples, rounded, through the colour map; kFanBackground outside.
    /// The interpolation weights are kept to 1/kWeightOne (15 bits).
    /// Kernel::Portable forces the portable four-pixel loop (tests compare it with the default, which uses
    /// AVX2 gathers where the CPU has them; both give the same pixels).
    enum class Kernel { Best, Portable };
    Image8 apply(const PolarImage& img, const DisplayParams& display, Kernel kernel = Kernel::Best) const;
    /// The same fan written into `out` (its pixels resized to the fan; every byte written, so a buffer kept
    /// from an earlier fan needs no clearing).
    void apply_into(const PolarImage& img, const DisplayParams& display, Image8& out,
                    Kernel kernel = Kernel::Best) const;
    /// Paints in `rgb` the pixels of `fan` (this resampler's apply of `img`) whose nearest sample in (bin,
    /// beam) has no echo (level -inf): the map is the taps', so no pixel is mapped twice (parallel over
    /// rows).
    void paint_no_echo(const PolarImage& img, const std::array<std::uint8_t, 3>& rgb, Image8& fan) const;
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
    std::shared_ptr<const SonarGrid> grid_;
    int height_px_;
    SectorLayout layout_;
    // The taps, one array per field (apply reads four at a time); allocated without clearing, since the
    // constructor writes every element (7.6 M taps, 60 MB, for a 512 x 2048 fan).
    std::unique_ptr<std::int32_t[]> tap_index_;
    std::unique_ptr<std::uint16_t[]> tap_wb_, tap_wi_;
    std::vector<Run> runs_;
    std::vector<std::uint32_t> row_runs_; ///< runs of row y: runs_[row_runs_[y], row_runs_[y + 1])
};

/// The sector-formed image (RGB): bilinear in (bin, beam) of the gray levels, then the colour map.
Image8 sector_image(const PolarImage& img, const SonarParams& sonar, const DisplayParams& display,
                    int height_px = 0);

/// Background colour outside the fan.
constexpr std::array<std::uint8_t, 3> kFanBackground{24, 26, 32};

} // namespace sonarsim

// The display range an image is shown with (display.auto).
#pragma once
#include "core/grid/sonar_grid.hpp"
#include "core/data/polar_image.hpp"

namespace sonarsim {

/// The display range an image is shown with: `display` itself, or with display.auto its lo/hi replaced by
/// the 5th and 99.5th percentiles of the image's finite levels as the fan shows them (each sample weighted
/// by its range, as the fan's area is; a histogram of 4096 bins, interpolated), at most kAutoDisplaySpanDb
/// and at least 1 dB apart. An image with no finite level keeps lo_db and hi_db.
DisplayParams effective_display(const PolarImage& img, const DisplayParams& display, const SonarGrid& grid);
inline DisplayParams effective_display(const PolarImage& img, const DisplayParams& display,
                                       const SonarParams& sonar) {
    return effective_display(img, display, *sonar_grid(sonar));
}

/// The same for an image whose every sample shows as one pixel (a side-scan waterfall, a scan's raw array).
DisplayParams effective_display(const PolarImage& img, const DisplayParams& display);

/// Half a grey level of a display range shown in 256 levels [dB]: the screen's precision, the error below
/// which a level shows as the same grey.
inline double half_grey_level_db(const DisplayParams& shown) {
    return 0.5 * (shown.hi_db - shown.lo_db) / 255;
}

/// Widest automatic display range [dB]: a scene whose echoes stand 100 dB above its noise still shows the
/// texture of its echoes (speckle spans about 20 dB).
constexpr double kAutoDisplaySpanDb = 50;

} // namespace sonarsim

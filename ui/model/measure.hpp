// Measurements on the sonar image, GL-free: the distance between two image places, and dB statistics of the
// region they span (range r0..r1 x azimuth a0..a1: a rectangle in the raw polar image, an annular sector in
// the fan).
#pragma once
#include "ui/model/sonar_geometry.hpp"

#include "core/display/image.hpp"

namespace sonarsim::ui {

/// Distance [m] between two places in the image plane (x = r cos a, y = r sin a): what a ruler laid on the
/// fan measures.
double image_distance_m(const ImagePlace& a, const ImagePlace& b);

struct RegionStats {
    int cells = 0;      ///< (bin, beam) cells whose centres lie in the region
    int echo_cells = 0; ///< of which something echoes (finite L_EN)
    double min_db = 0, max_db = 0;
    double mean_db = 0;   ///< 10 log10 of the mean intensity of the echoing cells
    double median_db = 0; ///< median L_EN of the echoing cells
};

/// Statistics of the cells with centres in [min r, max r] x [min a, max a] of the two places.
RegionStats region_stats(const PolarImage& image, const SonarParams& sonar, const ImagePlace& a,
                         const ImagePlace& b);

} // namespace sonarsim::ui

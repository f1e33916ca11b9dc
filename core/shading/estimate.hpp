// The sampling error of an image whose hits form two independent halves (jittered placement), estimated
// from the hits and the scene alone, so that a re-shade re-estimates it without tracing.
#pragma once
#include "core/data/hits.hpp"
#include "core/data/scene.hpp"

#include <limits>
#include <vector>

namespace sonarsim {

/// Per (range bin, sample beam) [bin * beams + k], linear relative to a fixed level: the image and its
/// estimated error, and the error's two terms.
struct BinErrors {
    int bins = 0, beams = 0;
    double ref_db = 0; ///< the level linear values are relative to [dB]
    std::vector<double> level, error, variance, footprint;
};

/// The errors of some beams (as an image of their own: cells[k] and coarse[k] are sample beam k's), from
///  - variance: |A - B| / 2, A and B the images of each half (Cell::half) alone at twice the weight: two
///    independent estimates of the same image, whose mean's error has the same expected size;
///  - footprint: |C - F| / 3, C the same rays with each one's cell the whole stratum (`coarse`), F the image:
///    footprint binning's bias falls in second order of the cell (three times the finer cells' bias).
/// A bin's error is sqrt(variance^2 + footprint^2). Linear levels are relative to `ref_db` (NaN: the
/// halves' strongest level).
BinErrors bin_errors(const TraceResult& cells, const std::vector<std::vector<Cell>>& coarse,
                     const SceneDesc& scene, double ref_db = std::numeric_limits<double>::quiet_NaN());

/// The image-wide estimate from bin errors: rel L1 = sum of errors / sum of levels, the dB quantiles those
/// of 10 log10(1 + error / level) over bins echoing.
TraceResult::ErrorEstimate summarise(const std::vector<const BinErrors*>& errors);

/// The estimate of a jittered image from its sample beams (TraceResult::coarse_cells non-empty); invalid
/// without halves.
TraceResult::ErrorEstimate estimate_error(const TraceResult& hits, const SceneDesc& scene);

} // namespace sonarsim

// The sampling error of an image whose hits form two independent halves (jittered placement), estimated
// from the hits and the scene alone, so that a re-shade re-estimates it without tracing.
#pragma once
#include "core/data/hits.hpp"
#include "core/data/scene.hpp"

namespace sonarsim {

/// Per bin of the sample beams (every `stride`-th beam with cells), two terms:
///  - variance: |A - B| / 2, A and B the images of each half alone (each an unbiased estimate of the same
///    image at twice the weight; the image is their mean, whose error has the same expected size);
///  - footprint: |W - F|, W the image of the same cells with each footprint twice as wide about its ray:
///    footprint binning's bias grows with the cell (first order at edges, which this counts in full).
/// A bin's error is sqrt(variance^2 + footprint^2); rel L1 is their sum over the sum of the image, the dB
/// quantiles those of 10 log10(1 + error / level) over bins echoing. Invalid without halves.
TraceResult::ErrorEstimate estimate_error(const TraceResult& hits, const SceneDesc& scene);

} // namespace sonarsim

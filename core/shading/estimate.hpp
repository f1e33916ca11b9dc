// The sampling error of an image whose hits form two independent halves (jittered placement), estimated
// from the hits and the scene alone, so that a re-shade re-estimates it without tracing.
#pragma once
#include "core/data/hits.hpp"
#include "core/data/scene.hpp"

namespace sonarsim {

/// The error of a jittered image, from its sample beams (those with TraceResult::stratum_cells), per bin:
///  - variance: |A - B| / 2, A and B the images of each half (Cell::half) alone at twice the weight: two
///    independent estimates of the same image, whose mean's error has the same expected size;
///  - footprint: |C - F| / 3, C the image of the same rays with each one's cell its whole stratum, F the
///    image: footprint binning's bias falls in second order of the cell, so C's is about four times F's.
/// A bin's error is sqrt(variance^2 + footprint^2); rel L1 is their sum over the sum of the levels, the dB
/// quantiles those of 10 log10(1 + error / level) over bins echoing. Invalid without halves.
TraceResult::ErrorEstimate estimate_error(const TraceResult& hits, const SceneDesc& scene);

} // namespace sonarsim

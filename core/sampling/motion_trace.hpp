// Tracing a frame taken while the sonar moves (sampling/acquisition.hpp): each (ping, range slab) is traced
// from the sonar's pose at its receive time with the placement the scene asks for, over that ping's beams
// only (TraceControl::beams), and the frame keeps, per beam, the echoes of its own ping that arrive in each
// slab. An echo's range is half its two-way path: from the transmit position to the scatterer and back to the
// receive position.
#pragma once
#include "core/sampling/trace.hpp"

#include <vector>

namespace sonarsim {

/// The frame of a moving sonar; with zero velocity and rates, trace() does not come here.
TraceResult trace_moving(const SceneGeometry& geometry, const SceneDesc& scene, const TraceControl& control);

namespace detail {
/// One (ping, slab) trace's error estimate and the weights of its part of the frame: its echo (linear sum
/// over its image) and its echoing bins.
struct SlotEstimate {
    TraceResult::ErrorEstimate e;
    double echo = 0, bins = 0;
};
/// The frame's estimate from its slots': the rel L1 of the whole (their |error| sums over their echo sums,
/// so that a slab with little echo counts for little), the median as the slots' medians weighted by their
/// echoing bins (the whole's lies between theirs), the 95th percentile and the passes the largest. Without
/// echo to weigh by, the largest of each.
TraceResult::ErrorEstimate combine_slot_estimates(const std::vector<SlotEstimate>& slots);
} // namespace detail

} // namespace sonarsim

// Tracing a frame taken while the sonar moves (sampling/acquisition.hpp): each (ping, range slab) is traced
// from the sonar's pose at its receive time with the placement the scene asks for, over that ping's beams
// only (TraceControl::beams), and the frame keeps, per beam, the echoes of its own ping that arrive in each
// slab. An echo's range is half its two-way path: from the transmit position to the scatterer and back to the
// receive position.
#pragma once
#include "core/sampling/trace.hpp"

namespace sonarsim {

/// The frame of a moving sonar; with zero velocity and rates, trace() does not come here.
TraceResult trace_moving(const SceneGeometry& geometry, const SceneDesc& scene, const TraceControl& control);

} // namespace sonarsim

// The controls panel's readout: absorption, frame and image times, and what the shown image cost (a frame's
// stages, rays and the sampler's estimate against its tolerances; a side-scan's or scan's profiles).
#pragma once
#include "ui/model/session.hpp"

namespace sonarsim::ui {

/// Draws the readout lines into the current ImGui window; `frame_ms` the viewer's last frame.
void draw_readout(Session& session, double frame_ms);

} // namespace sonarsim::ui

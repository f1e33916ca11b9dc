// The interactive viewer: GLFW window, Dear ImGui panels, the 3D view and the live sonar image.
#pragma once
#include "core/data/scene.hpp"

#include <glm/glm.hpp>
#include <array>
#include <optional>
#include <string>

namespace sonarsim::ui {

struct ViewerOptions {
    SceneDesc scene;
    int frames = 0;         ///< > 0: draw this many frames, then exit (each frame waits for its image)
    std::string screenshot; ///< PNG of the whole window after the last frame
    bool orbit = false;     ///< move the sonar every frame (forces a retrace); print timings as JSON at exit
    /// With orbit: a frame shows the image of the previous frame's pose while the worker traces the current
    /// one. Otherwise (default) each frame waits for the image of its own pose.
    bool orbit_pipelined = false;
    /// With orbit: request each pose as a drag does (a preview, TraceControl::preview) and time that path.
    bool orbit_preview = false;
    int width = 1280, height = 800;
    std::string snapshot; ///< after the last frame, write a snapshot (as the S key does) to this prefix
    std::optional<glm::dvec2> mouse; ///< headless: hold the mouse at this window pixel (hover feedback)
    /// Headless: a scripted left-button drag from `drag[0]` to `drag[1]` (window pixels) over the frames.
    std::optional<std::array<glm::dvec2, 2>> drag;
    std::string script;    ///< timed mouse and key events replayed through the GLFW callbacks (script.hpp)
    std::string state;     ///< after the last frame: camera, pose, objects, selection, undo depth as JSON
    float ui_scale = 1.0f; ///< the user's UI scale (View -> UI scale), times the monitor's content scale
    std::string layout;    ///< after the last frame: every text run on screen as JSON, with overlaps found
};

/// Opens the window and runs until it is closed (or `frames` have been drawn). Returns the exit status.
/// Throws std::runtime_error when no window can be opened.
int run_viewer(const ViewerOptions& options);

} // namespace sonarsim::ui

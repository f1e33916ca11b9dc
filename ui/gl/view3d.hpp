// The 3D view as a PNG with no display at all (EGL on Mesa's surfaceless platform): `sonarsim render
// --view3d`. GL-free header: callers need no OpenGL headers.
#pragma once
#include "core/data/scene.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace sonarsim::ui {

/// The 3D view of `scene` (scene, sonar, field of view) from its default camera as PNG bytes. Throws
/// InputError for a bad mesh, std::runtime_error when no headless OpenGL context can be made.
std::vector<std::uint8_t> view3d_png_headless(const SceneDesc& scene, int w, int h);

/// Writes the headless 3D view PNG to `path` atomically.
void write_view3d_png(const SceneDesc& scene, const std::string& path, int w = 1024, int h = 768);

} // namespace sonarsim::ui

// Meshes for drawing only: software OpenGL (llvmpipe) draws a few hundred thousand triangles per frame
// comfortably, not millions. Above a budget the 3D view draws a vertex-clustered copy; tracing always uses
// the full mesh.
#pragma once
#include "core/geometry/mesh.hpp"

#include <cstddef>
#include <memory>
#include <vector>

namespace sonarsim::ui {

/// Triangles the 3D view draws at most, over all objects. On this project's 2-core machine under Mesa
/// llvmpipe the 2 M-triangle terrain's orbit (a full image every frame) took 71 ms a frame at 300 k (252 k
/// drawn), 43 ms at 100 k and 30 ms at 50 k: the frame budget of 33 ms holds at 50 k.
constexpr std::size_t kDisplayTriangles = 50000;

/// At most `max_triangles` triangles that look like `mesh`: vertex clustering on a uniform grid over its
/// bounds (the vertices in a cell merge into their mean; triangles that collapse or repeat are dropped), the
/// cell as small as the budget allows. A mesh within the budget is returned unchanged.
TriMesh simplify_for_display(const TriMesh& mesh, std::size_t max_triangles);

/// Every mesh simplified to its share of `max_triangles` (meshes smaller than an equal share keep all their
/// triangles and leave the rest to the larger ones); unchanged when they all fit.
/// Meshes within their share are returned as the same pointer (not copied).
std::vector<std::shared_ptr<const TriMesh>>
simplify_for_display(const std::vector<std::shared_ptr<const TriMesh>>& meshes, std::size_t max_triangles);

} // namespace sonarsim::ui

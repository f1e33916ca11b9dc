// Procedural benchmark terrain: a smooth, deterministic height field written as a binary PLY grid.
#pragma once
#include <string>

namespace sonarsim::bench {

/// Side of the square terrain [m]; it spans [-kTerrainSize_m / 2, kTerrainSize_m / 2] in x and y.
constexpr double kTerrainSize_m = 40.0;

/// Height [m] of the terrain at (x, y) [m]: a sum of a few sinusoids and Gaussian bumps with fixed
/// parameters (relief of about +-3 m), so that a scene can put its sonar a given height above the ground.
double terrain_height_m(double x_m, double y_m);

/// Height [m] of the rough terrain at grid vertex (i, j) of an n x n grid over kRoughSize_m: the smooth
/// terrain stretched 6 times (relief about +-3 m), plus roughness that facets show at long range: value
/// noise of 6 m cells (+-0.6 m) and 1.5 m cells (+-0.3 m), and an independent +-0.4 m per vertex, all from
/// an integer hash (deterministic, the same on every machine).
constexpr double kRoughSize_m = 240.0;
double rough_height_m(int i, int j, int n);

/// Writes an n x n vertex grid of the terrain over the square (2 (n - 1)^2 triangles, normals +z) as a
/// binary little-endian PLY: `float x y z`, `list uchar int vertex_indices`; `rough`: the rough terrain over
/// kRoughSize_m instead. Throws std::runtime_error when the file cannot be written. The bytes depend only on
/// n and `rough`.
void write_terrain_ply(const std::string& path, int n, bool rough = false);

/// Triangles of the n x n grid.
inline long terrain_triangles(int n) {
    return 2L * (n - 1) * (n - 1);
}

} // namespace sonarsim::bench

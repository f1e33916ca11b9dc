#include "terrain.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <vector>

namespace sonarsim::bench {
namespace {

constexpr double kTwoPi = 6.283185307179586;

/// Appends v as 4 little-endian bytes, whatever the host's byte order.
void put_u32(std::vector<char>& out, std::uint32_t v) {
    for (int k = 0; k < 4; ++k) out.push_back(char((v >> (8 * k)) & 0xffu));
}
void put_f32(std::vector<char>& out, float f) {
    std::uint32_t u;
    static_assert(sizeof u == sizeof f, "32-bit float");
    std::memcpy(&u, &f, sizeof u);
    put_u32(out, u);
}

double bump(double x, double y, double x0, double y0, double sigma) {
    return std::exp(-((x - x0) * (x - x0) + (y - y0) * (y - y0)) / (2 * sigma * sigma));
}

} // namespace

double terrain_height_m(double x, double y) {
    return 1.1 * std::sin(kTwoPi * x / 17.0 + 0.3) * std::cos(kTwoPi * y / 23.0) +
           0.6 * std::sin(kTwoPi * (x + 0.7 * y) / 9.5 + 1.1) +
           0.25 * std::sin(kTwoPi * x / 3.7) * std::sin(kTwoPi * y / 4.3 + 0.5) +
           2.0 * bump(x, y, 6.0, -5.0, 4.0) - 1.6 * bump(x, y, -8.0, 7.0, 5.0) +
           1.2 * bump(x, y, -4.0, -11.0, 2.5);
}

void write_terrain_ply(const std::string& path, int n) {
    if (n < 2) throw std::runtime_error("terrain grid needs at least 2 x 2 vertices");
    const long nv = long(n) * n, nf = terrain_triangles(n);
    std::vector<char> out;
    char header[512];
    const int len = std::snprintf(header, sizeof header,
                                  "ply\nformat binary_little_endian 1.0\n"
                                  "comment sonarsim benchmark terrain: %d x %d grid over %.0f x %.0f m, "
                                  "bench/terrain.cpp\n"
                                  "element vertex %ld\nproperty float x\nproperty float y\nproperty float z\n"
                                  "element face %ld\nproperty list uchar int vertex_indices\nend_header\n",
                                  n, n, kTerrainSize_m, kTerrainSize_m, nv, nf);
    out.reserve(size_t(len) + size_t(nv) * 12 + size_t(nf) * 13);
    out.insert(out.end(), header, header + len);
    const double step = kTerrainSize_m / (n - 1);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const double x = -kTerrainSize_m / 2 + i * step, y = -kTerrainSize_m / 2 + j * step;
            put_f32(out, float(x)), put_f32(out, float(y)), put_f32(out, float(terrain_height_m(x, y)));
        }
    // Two counter-clockwise triangles (seen from +z) per grid cell.
    for (int j = 0; j + 1 < n; ++j)
        for (int i = 0; i + 1 < n; ++i) {
            const std::uint32_t v00 = std::uint32_t(j * n + i), v10 = v00 + 1, v01 = v00 + std::uint32_t(n),
                                v11 = v01 + 1;
            for (auto tri :
                 {std::array<std::uint32_t, 3>{v00, v10, v11}, std::array<std::uint32_t, 3>{v00, v11, v01}}) {
                out.push_back(char(3));
                for (std::uint32_t v : tri) put_u32(out, v);
            }
        }
    const std::string tmp = path + ".tmp";
    {
        std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
        f.write(out.data(), std::streamsize(out.size()));
        if (!f) throw std::runtime_error("cannot write " + tmp);
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0)
        throw std::runtime_error("cannot rename " + tmp + " to " + path);
}

} // namespace sonarsim::bench

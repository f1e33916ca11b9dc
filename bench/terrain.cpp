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

/// A uniform value in [-1, 1) from integer coordinates and a seed (a 64-bit mix).
double hash_unit(std::int64_t i, std::int64_t j, std::uint64_t seed) {
    std::uint64_t h = std::uint64_t(i) * 0x9E3779B97F4A7C15ull ^
                      (std::uint64_t(j) + 0x632BE59BD9B4E019ull) * 0xBF58476D1CE4E5B9ull ^ seed;
    h ^= h >> 31, h *= 0x94D049BB133111EBull, h ^= h >> 29, h *= 0xBF58476D1CE4E5B9ull, h ^= h >> 32;
    return double(h >> 11) * 0x1.0p-52 - 1.0;
}

/// Value noise on square cells of `cell_m`, smoothly interpolated (smoothstep), in [-1, 1].
double value_noise(double x, double y, double cell_m, std::uint64_t seed) {
    const double u = x / cell_m, v = y / cell_m;
    const double fu = std::floor(u), fv = std::floor(v), a = u - fu, b = v - fv;
    const double sa = a * a * (3 - 2 * a), sb = b * b * (3 - 2 * b);
    const auto i = std::int64_t(fu), j = std::int64_t(fv);
    const double n00 = hash_unit(i, j, seed), n10 = hash_unit(i + 1, j, seed),
                 n01 = hash_unit(i, j + 1, seed), n11 = hash_unit(i + 1, j + 1, seed);
    return (n00 * (1 - sa) + n10 * sa) * (1 - sb) + (n01 * (1 - sa) + n11 * sa) * sb;
}

} // namespace

double rough_height_m(int i, int j, int n) {
    const double step = kRoughSize_m / (n - 1), x = -kRoughSize_m / 2 + i * step,
                 y = -kRoughSize_m / 2 + j * step;
    const double k = kRoughSize_m / kTerrainSize_m;
    return terrain_height_m(x / k, y / k) + 0.6 * value_noise(x, y, 6.0, 1) +
           0.3 * value_noise(x, y, 1.5, 2) + 0.4 * hash_unit(i, j, 3);
}

double terrain_height_m(double x, double y) {
    return 1.1 * std::sin(kTwoPi * x / 17.0 + 0.3) * std::cos(kTwoPi * y / 23.0) +
           0.6 * std::sin(kTwoPi * (x + 0.7 * y) / 9.5 + 1.1) +
           0.25 * std::sin(kTwoPi * x / 3.7) * std::sin(kTwoPi * y / 4.3 + 0.5) +
           2.0 * bump(x, y, 6.0, -5.0, 4.0) - 1.6 * bump(x, y, -8.0, 7.0, 5.0) +
           1.2 * bump(x, y, -4.0, -11.0, 2.5);
}

void write_terrain_ply(const std::string& path, int n, bool rough) {
    if (n < 2) throw std::runtime_error("terrain grid needs at least 2 x 2 vertices");
    const double size_m = rough ? kRoughSize_m : kTerrainSize_m;
    const long nv = long(n) * n, nf = terrain_triangles(n);
    std::vector<char> out;
    char header[512];
    const int len = std::snprintf(header, sizeof header,
                                  "ply\nformat binary_little_endian 1.0\n"
                                  "comment sonarsim benchmark %s terrain: %d x %d grid over %.0f x %.0f m, "
                                  "bench/terrain.cpp\n"
                                  "element vertex %ld\nproperty float x\nproperty float y\nproperty float z\n"
                                  "element face %ld\nproperty list uchar int vertex_indices\nend_header\n",
                                  rough ? "rough" : "smooth", n, n, size_m, size_m, nv, nf);
    out.reserve(size_t(len) + size_t(nv) * 12 + size_t(nf) * 13);
    out.insert(out.end(), header, header + len);
    const double step = size_m / (n - 1);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const double x = -size_m / 2 + i * step, y = -size_m / 2 + j * step;
            put_f32(out, float(x)), put_f32(out, float(y));
            put_f32(out, float(rough ? rough_height_m(i, j, n) : terrain_height_m(x, y)));
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

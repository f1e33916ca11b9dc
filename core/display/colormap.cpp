#include "core/display/colormap.hpp"

#include <algorithm>
#include <cmath>

namespace sonarsim {

float gray_level(float level_db, double lo, double hi) {
    if (!(level_db > -INFINITY)) return 0.0f;
    return float(255.0 * std::clamp((double(level_db) - lo) / (hi - lo), 0.0, 1.0));
}

namespace {
/// A colour ramp through `n` evenly spaced key colours, interpolated linearly.
template <int N> std::array<std::uint8_t, 3> ramp(const double (&v)[N][3], double t) {
    const double x = t * (N - 1);
    const int i = std::min(N - 2, int(x));
    const double f = x - i;
    std::array<std::uint8_t, 3> c{};
    for (int k = 0; k < 3; ++k) c[size_t(k)] = std::uint8_t(std::lround(v[i][k] * (1 - f) + v[i + 1][k] * f));
    return c;
}
} // namespace

std::array<std::uint8_t, 3> colormap_rgb(Colormap map, double t) {
    t = std::clamp(t, 0.0, 1.0);
    switch (map) {
    case Colormap::Gray: {
        const auto g = std::uint8_t(std::lround(255 * t));
        return {g, g, g};
    }
    case Colormap::Copper: { // ARIS-like: black, brown, copper, pale gold
        static const double v[5][3] = {
            {0, 0, 0}, {70, 34, 12}, {160, 86, 36}, {232, 160, 78}, {255, 236, 184}};
        return ramp(v, t);
    }
    case Colormap::Hot: { // black, red, yellow, white
        static const double v[4][3] = {{0, 0, 0}, {230, 0, 0}, {255, 210, 0}, {255, 255, 255}};
        return ramp(v, t);
    }
    case Colormap::Viridis:
        break;
    }
    // Viridis, sampled at nine evenly spaced points and interpolated linearly.
    static const double v[9][3] = {{68, 1, 84},    {71, 44, 122},  {59, 81, 139},
                                   {44, 113, 142}, {33, 144, 141}, {39, 173, 129},
                                   {92, 200, 99},  {170, 220, 50}, {253, 231, 37}};
    return ramp(v, t);
}

std::array<std::array<std::uint8_t, 3>, 256> colormap_table(Colormap map) {
    std::array<std::array<std::uint8_t, 3>, 256> table;
    for (int g = 0; g < 256; ++g) table[size_t(g)] = colormap_rgb(map, g / 255.0);
    return table;
}

std::array<std::uint8_t, 3> no_echo_rgb(Colormap map) {
    // Unlike the low end of every map: dark blue beside black, black beside viridis' purple.
    return map == Colormap::Viridis ? std::array<std::uint8_t, 3>{0, 0, 0}
                                    : std::array<std::uint8_t, 3>{18, 42, 78};
}

} // namespace sonarsim

#include "core/kinds/kind_images.hpp"

#include "core/base/recent_shared.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

namespace sonarsim {
namespace {

constexpr float kNoEcho = -std::numeric_limits<float>::infinity();

/// The level at continuous bin coordinate u (bin k's centre at k): linear in dB between the two nearest
/// bins, the nearer one where the other has no echo; no echo outside [-1/2, bins - 1/2).
float level_at(const float* profile, int bins, double u) {
    if (!(u >= -0.5 && u < bins - 0.5)) return kNoEcho;
    const int k0 = std::clamp(int(std::floor(u)), 0, bins - 1), k1 = std::min(k0 + 1, bins - 1);
    const double w = std::clamp(u - k0, 0.0, 1.0);
    const float a = profile[k0], b = profile[k1];
    if (!std::isfinite(a) || !std::isfinite(b)) return w < 0.5 ? a : b;
    return float((1 - w) * a + w * b);
}

void paint(Image8& img, int x, int y, const std::array<std::uint8_t, 3>& rgb) {
    std::uint8_t* p = img.pixels.data() + (size_t(y) * size_t(img.width) + size_t(x)) * 3;
    p[0] = rgb[0], p[1] = rgb[1], p[2] = rgb[2];
}

} // namespace

PolarImage waterfall_levels(const PingSeries& s, SidescanRange range, double range_max_m) {
    PolarImage w;
    w.bins = s.pings, w.beams = 2 * s.bins;
    w.level_db.assign(size_t(w.bins) * size_t(w.beams), kNoEcho);
    const double ground_bin_m = range_max_m / s.bins;
    for (int p = 0; p < s.pings; ++p) {
        float* row = w.level_db.data() + size_t(p) * size_t(w.beams);
        const double h = s.first_return_m.empty() ? std::nan("") : s.first_return_m[size_t(p)];
        for (int side = 0; side < 2; ++side) {
            const float* profile = s.profile(p, side);
            for (int j = 0; j < s.bins; ++j) {
                float v = kNoEcho;
                if (range == SidescanRange::Slant) {
                    v = profile[j];
                } else if (std::isfinite(h)) {
                    const double g = (j + 0.5) * ground_bin_m, r = std::hypot(g, h);
                    if (r < range_max_m) v = level_at(profile, s.bins, s.grid->bin_position(r) - 0.5);
                }
                // Port runs from far (column 0) to near, starboard from near to far.
                row[side == 0 ? s.bins - 1 - j : s.bins + j] = v;
            }
        }
    }
    return w;
}

Image8 waterfall_image(const PolarImage& w, const DisplayParams& d) {
    Image8 img;
    img.width = w.beams, img.height = w.bins, img.channels = 3;
    img.pixels.resize(size_t(img.width) * size_t(img.height) * 3);
    const auto table = colormap_table(d.colormap);
    for (int y = 0; y < img.height; ++y) {
        const int ping = w.bins - 1 - y; // newest at the top
        for (int x = 0; x < img.width; ++x)
            paint(img, x, y, table[size_t(std::lround(gray_level(w.at(ping, x), d.lo_db, d.hi_db)))]);
    }
    return img;
}

PolarImage scan_levels(const PingSeries& s) {
    PolarImage a;
    a.bins = s.pings, a.beams = s.bins;
    a.level_db = s.level_db; // one channel: [step][bin]
    return a;
}

namespace {

/// Each pixel's step of the sweep (-1: none) and range bin, for one sweep's geometry: made once, read by
/// every sweep of that geometry (a viewer makes one a frame while a scan fills).
struct SweepMap {
    std::vector<std::int32_t> step, bin;
};

struct SweepKey {
    int size_px = 0, steps = 0;
    double start_deg = 0, step_deg = 0, range_max_m = 0;
    std::shared_ptr<const SonarGrid> grid;
    bool operator==(const SweepKey& o) const {
        return size_px == o.size_px && steps == o.steps && start_deg == o.start_deg &&
               step_deg == o.step_deg && range_max_m == o.range_max_m && grid == o.grid;
    }
};

std::shared_ptr<const SweepMap> sweep_map(const SweepKey& k) {
    static RecentShared<SweepKey, SweepMap, 4> kept;
    return kept.get(k, [&] {
        auto m = std::make_shared<SweepMap>();
        const size_t pixels = size_t(k.size_px) * size_t(k.size_px);
        m->step.assign(pixels, -1), m->bin.assign(pixels, 0);
        const int n = k.steps;
        const double dir = k.step_deg < 0 ? -1 : 1, pitch = std::abs(k.step_deg);
        const bool full = n > 1 && std::abs(n * pitch - 360) < 1e-6;
        const double c = 0.5 * k.size_px, m_per_px = k.range_max_m / c;
        for (int y = 0; y < k.size_px; ++y)
            for (int x = 0; x < k.size_px; ++x) {
                const double dx = x + 0.5 - c, dy = c - (y + 0.5); // dx toward starboard, dy forward
                const double r = std::hypot(dx, dy) * m_per_px;
                const double angle = std::atan2(-dx, dy) * 180 / 3.14159265358979323846; // toward port
                // Turned from the start in the sweep's direction, in [-half a step, 360 - half a step).
                double turned = std::fmod(dir * (angle - k.start_deg), 360.0);
                if (turned < 0) turned += 360;
                if (turned >= 360 - 0.5 * pitch) turned -= 360;
                int best = int(std::lround(turned / pitch));
                if (full) best %= n;
                if (n == 1 && std::abs(turned) > 0.5 * pitch) best = -1; // one step: its own width only
                const double u = k.grid->bin_position(r);
                if (best < 0 || best >= n || r >= k.range_max_m || u < 0) continue;
                const size_t at = size_t(y) * size_t(k.size_px) + size_t(x);
                m->step[at] = best;
                m->bin[at] = std::min(int(u), k.grid->bins - 1);
            }
        return std::shared_ptr<const SweepMap>(std::move(m));
    });
}

} // namespace

Image8 sweep_image(const PingSeries& s, const DisplayParams& d, double range_max_m, int size_px) {
    Image8 img;
    img.width = img.height = size_px, img.channels = 3;
    img.pixels.resize(size_t(size_px) * size_t(size_px) * 3);
    const auto table = colormap_table(d.colormap);
    const auto none = no_echo_rgb(d.colormap);
    // The steps are evenly spaced (sweep_head_angles_deg): a pixel's step is the nearest by its angle. The
    // sweep's step i is the ping whose count is i modulo the steps (a scene's own sweep counts 0 ... n - 1;
    // one along a trajectory holds the newest n steps, from wherever the sweep was).
    const int n = s.pings;
    const std::int64_t oldest = s.schedule.front().number;
    const auto holding = [&](std::int64_t step_index) { // the series' ping of the sweep's step
        return int((((step_index - oldest) % n) + n) % n);
    };
    SweepKey key;
    key.size_px = size_px, key.steps = n, key.range_max_m = range_max_m, key.grid = s.grid;
    key.start_deg = s.schedule[size_t(holding(0))].head_deg;
    key.step_deg = n > 1 ? s.schedule[size_t(holding(1))].head_deg - key.start_deg : 360.0;
    const auto map = sweep_map(key);
    for (int y = 0; y < size_px; ++y)
        for (int x = 0; x < size_px; ++x) {
            const size_t at = size_t(y) * size_t(size_px) + size_t(x);
            const std::int32_t step = map->step[at];
            if (step < 0) {
                paint(img, x, y, none);
                continue;
            }
            const float v = s.profile(holding(step), 0)[map->bin[at]];
            paint(img, x, y, table[size_t(std::lround(gray_level(v, d.lo_db, d.hi_db)))]);
        }
    return img;
}

} // namespace sonarsim

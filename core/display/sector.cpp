#include "core/display/sector.hpp"

#include "core/data/pose.hpp"
#include "core/base/scratch_pool.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#if defined(__x86_64__)
#include <immintrin.h>
#endif
#include <stdexcept>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace sonarsim {

namespace {

/// std::lround for v >= 0 (halves away from zero), without a library call: v - trunc(v) is exact.
inline int round_half_up(float v) {
    const int i = int(v);
    return v - float(i) >= 0.5f ? i + 1 : i;
}

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define SONARSIM_FAN_AVX2 1
/// Eight fan pixels with AVX2 gathers: the same float operations, in the same order, as the portable loop
/// in SectorResampler::apply. Writes 28 bytes from `dst`: the ten pixels from `dst` on must be in the run
/// (the last four bytes are overwritten by the pixels after these eight).
__attribute__((target("avx2"))) void fan_pixels8_avx2(const float* gray, std::ptrdiff_t up,
                                                      const std::int32_t* index, const std::uint16_t* wb,
                                                      const std::uint16_t* wi, const std::uint32_t* lut,
                                                      std::uint8_t* dst) {
    const __m256 unit = _mm256_set1_ps(1.0f / SectorResampler::kWeightOne), one = _mm256_set1_ps(1.0f);
    const __m256i idx = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(index));
    const __m256 tb = _mm256_mul_ps(
        _mm256_cvtepi32_ps(_mm256_cvtepu16_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(wb)))),
        unit);
    const __m256 ti = _mm256_mul_ps(
        _mm256_cvtepi32_ps(_mm256_cvtepu16_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(wi)))),
        unit);
    const __m256 g00 = _mm256_i32gather_ps(gray, idx, 4), g01 = _mm256_i32gather_ps(gray + 1, idx, 4);
    const __m256 g10 = _mm256_i32gather_ps(gray + up, idx, 4),
                 g11 = _mm256_i32gather_ps(gray + up + 1, idx, 4);
    const __m256 ui = _mm256_sub_ps(one, ti);
    const __m256 near = _mm256_add_ps(_mm256_mul_ps(ui, g00), _mm256_mul_ps(ti, g01));
    const __m256 far = _mm256_add_ps(_mm256_mul_ps(ui, g10), _mm256_mul_ps(ti, g11));
    const __m256 v = _mm256_add_ps(_mm256_mul_ps(_mm256_sub_ps(one, tb), near), _mm256_mul_ps(tb, far));
    const __m256i t = _mm256_cvttps_epi32(v); // round_half_up
    const __m256 half =
        _mm256_cmp_ps(_mm256_sub_ps(v, _mm256_cvtepi32_ps(t)), _mm256_set1_ps(0.5f), _CMP_GE_OQ);
    const __m256i g =
        _mm256_min_epi32(_mm256_sub_epi32(t, _mm256_castps_si256(half)), _mm256_set1_epi32(255));
    const __m256i rgb0 = _mm256_i32gather_epi32(reinterpret_cast<const int*>(lut), g, 4);
    // Per 128-bit lane: the three colour bytes of its four pixels, packed into 12 bytes.
    const __m256i pack = _mm256_setr_epi8(0, 1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, -1, -1, -1, -1, 0, 1, 2, 4,
                                          5, 6, 8, 9, 10, 12, 13, 14, -1, -1, -1, -1);
    const __m256i rgb = _mm256_shuffle_epi8(rgb0, pack);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(dst), _mm256_castsi256_si128(rgb));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(dst + 12), _mm256_extracti128_si256(rgb, 1));
}
#endif

} // namespace

SectorLayout::SectorLayout(std::shared_ptr<const SonarGrid> grid, int height_px)
    : grid_(std::move(grid)), fan_(grid_->fan_layout(height_px)) {}

bool SectorLayout::pixel_to_polar(double px, double py, double& r, double& a_deg) const {
    const double x = (px - fan_.width_px / 2.0) * fan_.m_per_px,
                 y = (fan_.height_px - py) * fan_.m_per_px + fan_.y0_m;
    r = std::hypot(x, y);
    a_deg = rad2deg(std::atan2(-x, y));
    return grid_->inside(r, a_deg);
}

void SectorLayout::polar_to_pixel(double r, double a_deg, double& px, double& py) const {
    const double a = deg2rad(a_deg);
    px = fan_.width_px / 2.0 - r * std::sin(a) / fan_.m_per_px;
    py = fan_.height_px - (r * std::cos(a) - fan_.y0_m) / fan_.m_per_px;
}

void SectorLayout::polar_to_index(double r, double a_deg, double& bin, double& beam) const {
    bin = grid_->bin_position(r) - 0.5;
    beam = grid_->beam_index_of_azimuth_deg(a_deg);
}

SectorResampler::SectorResampler(std::shared_ptr<const SonarGrid> grid, int height_px)
    : grid_(std::move(grid)), height_px_(height_px),
      layout_(grid_, height_px > 0 ? height_px : grid_->default_fan_height_px()) {
    const SonarGrid& g = *grid_;
    const int W = layout_.width(), H = layout_.height(), K = g.bins, N = g.beams;
    const double m = layout_.metres_per_pixel(), half = g.fan_half_rad;
    const double dr = g.bin_m, r0 = g.range_min_m, y0 = g.fan_layout(H).y0_m, r_max = g.range_max_m;
    // x >= 0: x * 2^15 + 1/2 is exact, so its floor is std::lround(x * 2^15) (no library call).
    auto weight = [](double x) { return std::uint16_t(x * kWeightOne + 0.5); };
    // `bin` is (r - r0) / dr - 0.5, the same for a pixel and its mirror image.
    auto tap = [&g, K, N, weight](double bin, double a, int& hint) {
        const double fb = std::clamp(bin, 0.0, K - 1.0),
                     fi = std::clamp(g.beam_index_of_azimuth_deg(a, hint), 0.0, N - 1.0);
        const int b0 = std::min(int(fb), K - 1), i0 = std::min(int(fi), N - 1);
        return Tap{b0 * (N + 1) + i0, weight(fb - b0), weight(fi - i0)};
    };
    // Each row (in parallel) finds its pixels inside the fan and their taps, then the rows are concatenated.
    // The two transcendental functions per pixel are the cost: a row visits only the pixels near the fan
    // (two pixels of margin on its analytic bounds), and only its left half: pixel W-1-px lies at -x, the
    // same range and the opposite azimuth (exactly: x is negated exactly, hypot and atan2 are symmetric).
    std::vector<std::vector<Tap>> row_taps(static_cast<size_t>(H));
    std::vector<std::vector<Run>> row_runs(static_cast<size_t>(H));
    tbb::parallel_for(tbb::blocked_range<int>(0, H, 8), [&](const tbb::blocked_range<int>& rows) {
        struct Inside {
            int px;
            double bin, a;
            bool port, starboard; ///< the pixel, and its mirror image, lie in the fan
        };
        std::vector<Inside> left;
        for (int py = rows.begin(); py < rows.end(); ++py) {
            const double y = (H - (py + 0.5)) * m + y0; // as in SectorLayout
            if (y > r_max + m || (half < kPi / 2 && y < -m)) continue;
            double x_max = std::sqrt(std::max(0.0, r_max * r_max - y * y));
            if (half < kPi / 2) x_max = std::min(x_max, std::max(0.0, y) * std::tan(half));
            const int px_begin = std::max(0, int(std::floor(W / 2.0 - 0.5 - x_max / m)) - 2);
            left.clear();
            double r, a;
            for (int px = px_begin; px < (W + 1) / 2; ++px) {
                const bool port = layout_.pixel_to_polar(px + 0.5, py + 0.5, r, a),
                           starboard = g.inside(r, -a);
                if (port || starboard) left.push_back({px, (r - r0) / dr - 0.5, a, port, starboard});
            }
            std::vector<Tap>& taps = row_taps[size_t(py)];
            std::vector<Run>& runs = row_runs[size_t(py)];
            auto add = [&](int px, const Tap& t) {
                if (runs.empty() || runs.back().x1 != px)
                    runs.push_back({px, px, std::uint32_t(taps.size())});
                ++runs.back().x1;
                taps.push_back(t);
            };
            taps.reserve(2 * left.size());
            int hint = 0; // the azimuth decreases from port to starboard: each tap's beam from the last one's
            for (const Inside& p : left)
                if (p.port) add(p.px, tap(p.bin, p.a, hint));
            for (auto p = left.rbegin(); p != left.rend(); ++p)
                if (p->starboard && W - 1 - p->px != p->px) add(W - 1 - p->px, tap(p->bin, -p->a, hint));
        }
    });
    row_runs_.assign(size_t(H) + 1, 0);
    std::vector<size_t> row_first(size_t(H) + 1, 0);
    for (int y = 0; y < H; ++y) {
        row_runs_[size_t(y) + 1] = row_runs_[size_t(y)] + std::uint32_t(row_runs[size_t(y)].size());
        row_first[size_t(y) + 1] = row_first[size_t(y)] + row_taps[size_t(y)].size();
    }
    const size_t taps = row_first[size_t(H)];
    tap_index_.reset(new std::int32_t[taps]), tap_wb_.reset(new std::uint16_t[taps]);
    tap_wi_.reset(new std::uint16_t[taps]);
    runs_.resize(row_runs_[size_t(H)]);
    tbb::parallel_for(0, H, [&](int y) {
        size_t n = row_first[size_t(y)];
        for (const Tap& t : row_taps[size_t(y)])
            tap_index_[n] = t.index, tap_wb_[n] = t.wb, tap_wi_[n++] = t.wi;
        Run* out = runs_.data() + row_runs_[size_t(y)];
        for (Run run : row_runs[size_t(y)]) {
            run.first += std::uint32_t(row_first[size_t(y)]);
            *out++ = run;
        }
    });
}

Image8 SectorResampler::apply(const PolarImage& img, const DisplayParams& d, Kernel kernel) const {
    Image8 out;
    apply_into(img, d, out, kernel);
    return out;
}

void SectorResampler::apply_into(const PolarImage& img, const DisplayParams& d, Image8& out,
                                 Kernel kernel) const {
    const int K = img.bins, N = img.beams;
    if (K != grid_->bins || N != grid_->beams)
        throw std::invalid_argument("SectorResampler: the image is not of the sonar it was built for");
    // Gray level of every sample once, padded with a copy of the last bin and of the last beam.
    const double lo = d.lo_db, span = d.hi_db - d.lo_db;
    std::vector<float> gray = scratch::take<float>(size_t(K + 1) * size_t(N + 1)); // every value written
    tbb::parallel_for(tbb::blocked_range<int>(0, K + 1, 64), [&](const tbb::blocked_range<int>& bins) {
        for (int b = bins.begin(); b < bins.end(); ++b) {
            const float* in = img.level_db.data() + size_t(std::min(b, K - 1)) * size_t(N);
            float* out = gray.data() + size_t(b) * size_t(N + 1);
            for (int i = 0; i < N; ++i) { // gray_level, written so that it vectorises
                const double t = (double(in[i]) - lo) / span;
                const float g = float(255.0 * (t < 0.0 ? 0.0 : 1.0 < t ? 1.0 : t));
                out[i] = in[i] > -INFINITY ? g : 0.0f;
            }
            out[N] = out[N - 1];
        }
    });
    // RGB of each gray level in the low three bytes (little-endian order of the bytes in memory).
    std::array<std::uint32_t, 256> lut;
    const auto table = colormap_table(d.colormap);
    for (int g = 0; g < 256; ++g) {
        const std::uint8_t rgba[4] = {table[size_t(g)][0], table[size_t(g)][1], table[size_t(g)][2], 0};
        std::memcpy(&lut[size_t(g)], rgba, 4);
    }

    out.width = layout_.width(), out.height = layout_.height(), out.channels = 3;
    out.pixels.resize(size_t(out.width) * size_t(out.height) * 3); // every pixel written below
    const float* const G = gray.data();
    const std::int32_t* const I = tap_index_.get();
    const std::uint16_t *const WB = tap_wb_.get(), *const WI = tap_wi_.get();
    const Run* const R = runs_.data();
    const std::uint32_t* const row_runs = row_runs_.data();
    const std::uint32_t* const C = lut.data();
    std::uint8_t* const P = out.pixels.data();
    const int W = out.width;
    const std::ptrdiff_t up = N + 1; // next bin in the padded image
    constexpr float unit = 1.0f / kWeightOne;
#ifdef SONARSIM_FAN_AVX2
    static const bool has_avx2 = __builtin_cpu_supports("avx2");
    const bool avx2 = has_avx2 && kernel == Kernel::Best;
#else
    (void)kernel;
#endif
    // One pixel, and four at a time with the same operations in the same order (so the same floats).
    auto pixel = [=](std::uint32_t k) {
        const float* g = G + I[k];
        const float tb = float(WB[k]) * unit, ti = float(WI[k]) * unit;
        const float v = (1 - tb) * ((1 - ti) * g[0] + ti * g[1]) + tb * ((1 - ti) * g[up] + ti * g[up + 1]);
        return C[std::min(round_half_up(v), 255)];
    };
    using F4 = float __attribute__((vector_size(16)));
    using I4 = std::int32_t __attribute__((vector_size(16)));
    using U4 = std::uint16_t __attribute__((vector_size(8)));
    auto pixels4 = [=](std::uint32_t k, std::uint8_t* dst) {
        I4 idx;
        U4 wb, wi;
        std::memcpy(&idx, I + k, sizeof idx);
        std::memcpy(&wb, WB + k, sizeof wb);
        std::memcpy(&wi, WI + k, sizeof wi);
        const F4 tb = __builtin_convertvector(wb, F4) * unit, ti = __builtin_convertvector(wi, F4) * unit;
        const float *g0 = G + idx[0], *g1 = G + idx[1], *g2 = G + idx[2], *g3 = G + idx[3];
        const F4 g00 = {g0[0], g1[0], g2[0], g3[0]}, g01 = {g0[1], g1[1], g2[1], g3[1]};
        const F4 g10 = {g0[up], g1[up], g2[up], g3[up]},
                 g11 = {g0[up + 1], g1[up + 1], g2[up + 1], g3[up + 1]};
        const F4 v = (1 - tb) * ((1 - ti) * g00 + ti * g01) + tb * ((1 - ti) * g10 + ti * g11);
        // round_half_up: truncate, then add one where the remainder is at least one half (v >= 0).
        const I4 t = __builtin_convertvector(v, I4);
        const I4 g = t - (v - __builtin_convertvector(t, F4) >= 0.5f);
        for (int j = 0; j < 4; ++j) std::memcpy(dst + 3 * j, &C[std::min(g[j], 255)], 4);
    };
    tbb::parallel_for(tbb::blocked_range<int>(0, out.height, 16), [=](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y < rows.end(); ++y) {
            std::uint8_t* const row = P + size_t(y) * size_t(W) * 3;
            auto background = [row](int x0, int x1) {
                for (int x = x0; x < x1; ++x)
                    row[3 * x] = kFanBackground[0], row[3 * x + 1] = kFanBackground[1],
                            row[3 * x + 2] = kFanBackground[2];
            };
            int x = 0;
            for (std::uint32_t r = row_runs[y]; r < row_runs[y + 1]; ++r) {
                const Run run = R[r];
                background(x, run.x0);
                // Each pixel is a 4-byte store whose fourth byte the next pixel overwrites; the run's last
                // pixel stores three bytes.
                std::uint32_t k = run.first;
                x = run.x0;
#ifdef SONARSIM_FAN_AVX2
                if (avx2)
                    for (; x + 10 <= run.x1; x += 8, k += 8)
                        fan_pixels8_avx2(G, up, I + k, WB + k, WI + k, C, row + 3 * x);
#endif
                for (; x + 4 < run.x1; x += 4, k += 4) pixels4(k, row + 3 * x);
                for (; x + 1 < run.x1; ++x, ++k) {
                    const std::uint32_t c = pixel(k);
                    std::memcpy(row + 3 * x, &c, 4);
                }
                const std::uint32_t c = pixel(k);
                std::memcpy(row + 3 * x, &c, 3);
                ++x;
            }
            background(x, W);
        }
    });
    scratch::give(std::move(gray));
}

void SectorResampler::paint_no_echo(const PolarImage& img, const std::array<std::uint8_t, 3>& rgb,
                                    Image8& fan) const {
    const int K = img.bins, N = img.beams;
    if (K != grid_->bins || N != grid_->beams || fan.width != layout_.width() ||
        fan.height != layout_.height() || fan.channels != 3)
        throw std::invalid_argument(
            "SectorResampler: the image or the fan is not of the sonar it was built for");
    constexpr std::uint16_t half = kWeightOne / 2; // a weight of one half or more: the next sample is nearer
    const double per_bin = 1.0 / (N + 1);
    tbb::parallel_for(tbb::blocked_range<int>(0, fan.height, 16), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y < rows.end(); ++y) {
            std::uint8_t* const row = fan.pixels.data() + size_t(y) * size_t(fan.width) * 3;
            for (std::uint32_t r = row_runs_[size_t(y)]; r < row_runs_[size_t(y) + 1]; ++r) {
                const Run run = runs_[r];
                for (std::int32_t x = run.x0, k = std::int32_t(run.first); x < run.x1; ++x, ++k) {
                    // index / (N + 1) by a product: (index + 1/2) / (N + 1) is at least 1 / (2 (N + 1))
                    // from an integer, far beyond the rounding of the product.
                    const std::int32_t index = tap_index_[size_t(k)],
                                       b0 = std::int32_t((index + 0.5) * per_bin);
                    const size_t b = size_t(b0 + (tap_wb_[size_t(k)] >= half)),
                                 i = size_t(index - b0 * (N + 1) + (tap_wi_[size_t(k)] >= half));
                    if (!(img.level_db[b * size_t(N) + i] > -INFINITY))
                        std::memcpy(row + 3 * x, rgb.data(), 3);
                }
            }
        }
    });
}

Image8 sector_image(const PolarImage& img, const SonarParams& s, const DisplayParams& d, int height_px) {
    return SectorResampler(s, height_px).apply(img, d);
}

} // namespace sonarsim

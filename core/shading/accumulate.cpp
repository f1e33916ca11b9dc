#include "core/shading/accumulate.hpp"

#include "core/data/pose.hpp"
#include "core/grid/sonar_grid.hpp"
#include "core/grid/sensor_patterns.hpp"
#include "core/shading/footprint.hpp"
#include "core/shading/log_sum.hpp"
#include "core/shading/shade.hpp"
#include "core/shading/truth_accumulator.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <tbb/parallel_for.h>

namespace sonarsim {
namespace {

constexpr double kNegInf = -std::numeric_limits<double>::infinity();
/// A cell over several azimuth sub-columns (the sensor's beam forming) spreads each sub-column's share over
/// that sub-column's own part of its range footprint when the footprint's azimuth extent exceeds this many
/// range bins and its elevation extent; otherwise over the whole footprint. Spreading over the whole smears
/// the cell's edges by what the other sub-columns span; where the elevation extent is the larger, the parts
/// change the image too little for their cost (bench/NOTEBOOK.md).
constexpr double kSubcolumnSpreadBins = 0.25;
constexpr size_t kMaxSubcolumns = 8; ///< azimuth_subcolumns() at most

/// What every beam of one pass shares: the scene's constants and the outputs, written per beam column.
struct Pass {
    const TraceResult& hits;
    const SceneDesc& s;
    ShadeConstants k;
    std::shared_ptr<const SonarGrid> held; ///< the scene's grid (the registry's, held while the pass runs)
    const SonarGrid& grid;
    int K, N, S;
    double r_min, r_max, dr;
    bool spread;
    glm::dmat3 R;
    glm::dvec3 origin;
    PolarImage* image = nullptr;
    SensorInputs* inputs = nullptr;
    GroundTruth* truth = nullptr;
    StrongestContribution* strongest = nullptr;
    std::vector<std::vector<LogSum>>* orders = nullptr; ///< [beam][order]
    size_t order_count = 1;
    SceneTexture texture_field;
    const SceneTexture* texture = nullptr; ///< null when no material has a texture

    /// `columns`: the output's columns (0: the grid's beams; otherwise column k is hits' beam k).
    Pass(const TraceResult& h, const SceneDesc& scene, int columns = 0)
        : hits(h), s(scene), k(shade_constants(scene)), held(sonar_grid(scene.sonar)), grid(*held),
          K(grid.bins), N(columns > 0 ? columns : grid.beams), S(azimuth_subcolumns(scene)),
          r_min(grid.range_min_m), r_max(grid.range_max_m), dr(grid.bin_m),
          spread(scene.sampling.binning == EchoBinning::Footprint),
          R(rotation_matrix(scene.sonar.pose.orientation_deg)), origin(to_glm(scene.sonar.pose.position_m)),
          texture_field(scene), texture(texture_field.none() ? nullptr : &texture_field) {}
};

/// One beam's sums; `Img`, `Sens`, `Gt`, `Ord`, `Str` say which channels it fills (compiled out otherwise).
template <bool Img, bool Sens, bool Gt, bool Ord, bool Str> class BeamPass {
  public:
    BeamPass(const Pass& p, int beam) : p_(p), i_(beam), cells_(p.hits, beam) {}

    void run() {
        const double x_max = contribution_levels(cells_, p_.s, p_.k, x_, p_.texture);
        if (x_max == kNegInf) return; // nothing echoes in this beam (nor in any path order)
        const size_t K = size_t(p_.K);
        const bool fine = Sens && p_.inputs->sub > 1, elevation = Sens && !p_.inputs->elevation_rad.empty();
        if constexpr (Img) lin_.assign(K, 0.0), hit_.assign(K, 0);
        if (fine) fine_.assign(K * size_t(p_.S), 0.0);
        if (elevation) wsum_.assign(K, 0.0), esum_.assign(K, 0.0);
        if constexpr (Gt) truth_.assign(K, TruthAccumulator{});
        if constexpr (Str) best_.assign(K, 0.0), best_n_.assign(K, -1);
        if constexpr (Ord) order_lin_.assign(p_.order_count, 0.0);
        std::vector<double> share(size_t(p_.S), 1.0);
        const double a_top = p_.grid.beam_port_edge_rad(i_), spacing = p_.grid.beam_width_rad(i_);
        for (size_t n = 0; n < cells_.size(); ++n) {
            if (x_[n] == kNegInf) continue;
            const Cell& c = cells_[n];
            const double w = std::exp(x_[n] - x_max);
            // Over several sub-columns whose parts of its range footprint differ: add_fine_parts.
            bool parts = false;
            if (fine) { // the cell's azimuth interval over the beam's sub-columns
                const double a0 = c.azimuth_rad - 0.5 * c.azimuth_width_rad, a1 = a0 + c.azimuth_width_rad;
                int in = 0;
                for (int q = 0; q < p_.S; ++q) {
                    const double hi = a_top - q * spacing / p_.S, lo = hi - spacing / p_.S;
                    share[size_t(q)] =
                        std::max(0.0, std::min(a1, hi) - std::max(a0, lo)) / c.azimuth_width_rad;
                    in += share[size_t(q)] > 0;
                }
                const double w_a = std::abs(double(c.range_a_hi_m) - c.range_a_lo_m);
                parts = in > 1 && p_.spread && w_a > kSubcolumnSpreadBins * p_.dr &&
                        w_a > std::abs(double(c.range_e_hi_m) - c.range_e_lo_m);
            }
            [[maybe_unused]] const GhostCell* ghost = cells_.ghost(n);
            [[maybe_unused]] std::uint64_t key = 0;
            [[maybe_unused]] unsigned bit = 0;
            [[maybe_unused]] double inc = 0, cos_a = 0, sin_a = 0, ghost_range = 0;
            [[maybe_unused]] double inside = 0; // the share of the echo inside the window
            if constexpr (Gt) { // the azimuth's sine and cosine once per cell (sonar_direction's products)
                cos_a = std::cos(double(c.azimuth_rad)), sin_a = std::sin(double(c.azimuth_rad));
                key = std::uint64_t(ghost ? ghost->order() : 0) << 32 | c.material;
                bit = c.material == kSurfaceMaterial ? 63u : std::min(c.material, 62u);
                inc = rad2deg(std::acos(std::clamp(double(c.cos_incidence), 0.0, 1.0)));
                if (ghost) ghost_range = glm::length(glm::dvec3(c.point_m) - p_.origin); // the scatterer's
            }
            detail::for_each_bin(c, p_.spread, p_.K, p_.r_min, p_.r_max, p_.dr, [&](int b, double frac) {
                const size_t bb = size_t(b);
                const double v = w * frac;
                if constexpr (Ord) inside += frac;
                if constexpr (Img) lin_[bb] += v, hit_[bb] = 1;
                if (fine && !parts)
                    for (int q = 0; q < p_.S; ++q)
                        fine_[bb * size_t(p_.S) + size_t(q)] += v * share[size_t(q)];
                if (elevation)
                    wsum_[bb] += v, esum_[bb] += v * detail::elevation_at(c, p_.grid.bin_centre_m(b));
                if constexpr (Gt)
                    if (v > 0) {
                        const double r = p_.grid.bin_centre_m(b), e = detail::elevation_at(c, r);
                        const double ce = std::cos(e);
                        const glm::dvec3 point =
                            ghost ? glm::dvec3(c.point_m)
                                  : p_.origin + r * (p_.R * glm::dvec3(ce * cos_a, ce * sin_a, std::sin(e)));
                        truth_[bb].add(v, e, inc, point, ghost ? ghost_range : r, key, bit);
                    }
                if constexpr (Str)
                    if (v > best_[bb]) best_[bb] = v, best_n_[bb] = std::int32_t(n);
            });
            if constexpr (Ord) add_order(n, w, inside);
            if (parts) add_fine_parts(c, w, share, a_top, spacing);
        }
        if constexpr (Img) write_image(x_max);
        if constexpr (Ord) write_orders(x_max);
        if (Sens) write_inputs(x_max, fine, elevation);
        if constexpr (Gt)
            for (int b = 0; b < p_.K; ++b) truth_[size_t(b)].write(*p_.truth, size_t(b) * p_.N + i_);
        if constexpr (Str)
            for (int b = 0; b < p_.K; ++b) p_.strongest->index[size_t(b) * p_.N + i_] = best_n_[size_t(b)];
    }

  private:
    /// A cell over several sub-columns: each gets its share of the echo (weight w) spread over its own part
    /// of the cell's range footprint (the range at the cell's azimuth edges, range_a_lo_m at the lower,
    /// taken as linear across the cell), not over the whole of it, which would smear the cell's edges in
    /// range by what the other sub-columns span. One walk over the bins for all the parts.
    void add_fine_parts(const Cell& c, double w, const std::vector<double>& share, double a_top,
                        double spacing) {
        struct Part {
            detail::Footprint f{0, 0, 0, 0};
            double v = 0, flat_lo = 0, flat_hi = 0, flat_share = 0, c_prev = 0;
            size_t q = 0;
        };
        std::array<Part, kMaxSubcolumns> parts;
        size_t n = 0;
        const double width = c.azimuth_width_rad, a0 = c.azimuth_rad - 0.5 * width;
        const double r = c.range_m, r_lo = double(c.range_a_lo_m) - r, r_hi = double(c.range_a_hi_m) - r;
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (int q = 0; q < p_.S && n < parts.size(); ++q) {
            if (!(share[size_t(q)] > 0)) continue;
            const double top = a_top - q * spacing / p_.S, bottom = top - spacing / p_.S;
            const double t0 = (std::max(a0, bottom) - a0) / width,
                         t1 = (std::min(a0 + width, top) - a0) / width;
            const detail::Footprint f(c.range_e_lo_m, c.range_e_hi_m, r_lo + t0 * (r_hi - r_lo),
                                      r_lo + t1 * (r_hi - r_lo));
            parts[n++] = {
                f, w * share[size_t(q)], f.lo + f.p, f.lo + f.q, f.q > 0 ? p_.dr / f.q : 0, 0, size_t(q)};
            lo = std::min(lo, f.lo), hi = std::max(hi, f.hi());
        }
        const int K = p_.K;
        const int b0 = int(std::clamp(std::floor((lo - p_.r_min) / p_.dr), 0.0, double(K)));
        const int b1 = int(std::clamp(std::floor((hi - p_.r_min) / p_.dr), -1.0, double(K - 1)));
        for (size_t k = 0; k < n; ++k) parts[k].c_prev = parts[k].f.cdf(p_.r_min + b0 * p_.dr);
        const size_t S = size_t(p_.S);
        for (int b = b0; b <= b1; ++b) {
            const double e0 = p_.r_min + b * p_.dr, e1 = b + 1 == K ? p_.r_max : e0 + p_.dr;
            for (size_t k = 0; k < n; ++k) {
                Part& x = parts[k];
                // Inside the flat top the cumulative share grows by dr / q per bin: no cdf to evaluate.
                const double c_next =
                    e0 >= x.flat_lo && e1 <= x.flat_hi && b + 1 < K ? x.c_prev + x.flat_share : x.f.cdf(e1);
                if (c_next > x.c_prev) fine_[size_t(b) * S + x.q] += x.v * (c_next - x.c_prev);
                x.c_prev = c_next;
            }
        }
    }

    /// Echo per path order: contribution n's share `inside` the window (summed over its bins in run()),
    /// summed linearly relative to the beam's peak (weight w, as the image) and written in the log domain
    /// once per beam (write_orders); a contribution too far below the peak for w goes there directly.
    void add_order(size_t n, double w, double inside) {
        if (!(inside > 0)) return;
        const GhostCell* g = cells_.ghost(n);
        const size_t order = std::min(p_.order_count - 1, size_t(g ? g->order() : 0));
        if (w > 0)
            order_lin_[order] += w * inside;
        else
            (*p_.orders)[size_t(i_)][order].add(x_[n] + std::log(inside));
    }
    void write_orders(double x_max) {
        for (size_t o = 0; o < order_lin_.size(); ++o)
            if (order_lin_[o] > 0) (*p_.orders)[size_t(i_)][o].add(x_max + std::log(order_lin_[o]));
    }

    void write_image(double x_max) {
        const int K = p_.K, N = p_.N;
        bool underflow = false;
        for (int b = 0; b < K; ++b) underflow |= hit_[size_t(b)] && !(lin_[size_t(b)] > 0);
        float* out = p_.image->level_db.data();
        if (underflow) {
            // Some bin lies more than ~3000 dB below the beam's peak: sum that beam in the log domain
            // instead.
            std::vector<LogSum> acc(static_cast<size_t>(K));
            for (size_t n = 0; n < cells_.size(); ++n)
                if (x_[n] != kNegInf)
                    detail::for_each_bin(
                        cells_[n], p_.spread, K, p_.r_min, p_.r_max, p_.dr,
                        [&](int b, double frac) { acc[size_t(b)].add(x_[n] + std::log(frac)); });
            for (int b = 0; b < K; ++b) {
                const double lv = acc[size_t(b)].log_value();
                if (lv != kNegInf) out[size_t(b) * N + i_] = float(lv / kLn10Over10 - p_.k.noise_level_db);
            }
            return;
        }
        for (int b = 0; b < K; ++b)
            if (lin_[size_t(b)] > 0)
                out[size_t(b) * N + i_] =
                    float((x_max + std::log(lin_[size_t(b)])) / kLn10Over10 - p_.k.noise_level_db);
    }

    void write_inputs(double x_max, bool fine, bool elevation) {
        SensorInputs& in = *p_.inputs;
        const int K = p_.K, N = p_.N, S = p_.S;
        for (int b = 0; b < K; ++b) {
            if (elevation && wsum_[size_t(b)] > 0)
                in.elevation_rad[size_t(b) * N + i_] = float(esum_[size_t(b)] / wsum_[size_t(b)]);
            for (int q = 0; fine && q < S; ++q)
                if (const double v = fine_[size_t(b) * S + q]; v > 0)
                    in.fine.level_db[size_t(b) * N * S + size_t(i_) * S + q] =
                        float((x_max + std::log(v)) / kLn10Over10 - p_.k.noise_level_db);
        }
    }

    const Pass& p_;
    const int i_;
    const BeamContributions cells_;
    std::vector<double> x_, lin_, fine_, wsum_, esum_, best_;
    std::vector<char> hit_;
    std::vector<TruthAccumulator> truth_;
    std::vector<double> order_lin_; ///< per path order: the echo inside the window, relative to the peak
    std::vector<std::int32_t> best_n_;
};

/// Runs BeamPass over every beam with the channels of `c` as template arguments.
template <bool... Fixed> void run_beams(const Pass& p, const Channels& c) {
    constexpr size_t n = sizeof...(Fixed);
    if constexpr (n == 5) {
        tbb::parallel_for(0, std::min(p.N, p.hits.beams), [&](int i) { BeamPass<Fixed...>(p, i).run(); });
    } else {
        const bool flags[5] = {c.image, c.sensor_inputs, c.ground_truth, c.path_orders, c.strongest};
        if (flags[n])
            run_beams<Fixed..., true>(p, c);
        else
            run_beams<Fixed..., false>(p, c);
    }
}

PolarImage empty_image(int bins, int beams) {
    PolarImage img;
    img.bins = bins, img.beams = beams;
    img.level_db.assign(size_t(bins) * size_t(beams), -std::numeric_limits<float>::infinity());
    return img;
}

} // namespace

bool needs_sensor_inputs(const SceneDesc& s) {
    return azimuth_subcolumns(s) > 1 || s.sensor.speckle != Speckle::Off;
}

const Accumulation& ImagePass::run(const TraceResult& hits, const SceneDesc& scene) {
    latest_ = std::make_shared<const Accumulation>(accumulate(hits, scene, channels_));
    return *latest_;
}

Accumulation accumulate(const TraceResult& hits, const SceneDesc& s, const Channels& c) {
    Pass p(hits, s);
    const size_t cells = size_t(p.K) * size_t(p.N);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    auto image = c.image ? std::make_shared<PolarImage>(empty_image(p.K, p.N)) : nullptr;
    auto inputs = c.sensor_inputs ? std::make_shared<SensorInputs>() : nullptr;
    if (inputs) {
        inputs->sub = p.S;
        if (p.S > 1) inputs->fine = empty_image(p.K, p.N * p.S);
        if (s.sensor.speckle != Speckle::Off) inputs->elevation_rad.assign(cells, nan);
    }
    auto truth = c.ground_truth ? std::make_shared<GroundTruth>(empty_ground_truth(p.K, p.N)) : nullptr;
    auto strongest = c.strongest ? std::make_shared<StrongestContribution>() : nullptr;
    if (strongest) strongest->bins = p.K, strongest->beams = p.N, strongest->index.assign(cells, -1);
    p.order_count = size_t(2 * std::max(0, s.sampling.bounces) + 1);
    std::vector<std::vector<LogSum>> orders(c.path_orders ? size_t(std::min(p.N, hits.beams)) : 0,
                                            std::vector<LogSum>(p.order_count));
    p.image = image.get(), p.inputs = inputs.get(), p.truth = truth.get(), p.strongest = strongest.get();
    p.orders = &orders;
    if (c.any()) run_beams<>(p, c);

    Accumulation out;
    out.image = std::move(image), out.inputs = std::move(inputs), out.truth = std::move(truth);
    out.strongest = std::move(strongest);
    if (c.path_orders) {
        out.path_order_db.resize(p.order_count);
        for (size_t o = 0; o < p.order_count; ++o) {
            LogSum total;
            for (auto& b : orders)
                if (b[o].s > 0) total.add(b[o].log_value());
            out.path_order_db[o] = total.log_value() / kLn10Over10;
        }
    }
    return out;
}

namespace {

PolarImage shade_image(const TraceResult& hits, const SceneDesc& s, int columns) {
    Pass p(hits, s, columns);
    PolarImage image = empty_image(p.K, p.N);
    p.image = &image;
    Channels c;
    c.image = true;
    run_beams<>(p, c);
    return image;
}

} // namespace

PolarImage shade(const TraceResult& hits, const SceneDesc& s) {
    return shade_image(hits, s, 0);
}

PolarImage shade_columns(const TraceResult& hits, const SceneDesc& s, int columns) {
    if (columns > s.sonar.beams) // each column is one of the scene's beams
        throw std::invalid_argument("shade_columns: " + std::to_string(columns) + " columns of " +
                                    std::to_string(s.sonar.beams) + " beams");
    return shade_image(hits, s, std::max(1, columns));
}

GroundTruth compute_ground_truth(const TraceResult& hits, const SceneDesc& s) {
    Channels c;
    c.ground_truth = true;
    return *accumulate(hits, s, c).truth;
}

} // namespace sonarsim

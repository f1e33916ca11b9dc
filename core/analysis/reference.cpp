#include "core/analysis/reference.hpp"

#include "core/grid/sonar_grid.hpp"
#include "core/grid/sensor_patterns.hpp"

#include "core/shading/physics.hpp"
#include "core/data/pose.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tbb/parallel_for.h>

namespace sonarsim {
namespace {

// 8-point Gauss-Legendre on [-1, 1].
constexpr double kGLx[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                            -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                            0.7966664774136267,  0.9602898564975363};
constexpr double kGLw[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873, 0.3626837833783620,
                            0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};

} // namespace

bool has_floor_reference(const SceneDesc& s) {
    return s.objects.empty() && s.seafloor.has_value();
}

PolarImage floor_reference(const SceneDesc& s, int panels) {
    const std::shared_ptr<const SonarGrid> grid = sonar_grid(s.sonar);
    const int N = grid->beams, K = grid->bins;
    const ElevationWeight pattern(s);
    const double phi = pattern.traced_fov_rad();
    const double r_min = grid->range_min_m, r_max = grid->range_max_m, dr = grid->bin_m;
    const glm::dmat3 R = rotation_matrix(s.sonar.pose.orientation_deg);
    const double H = s.seafloor->height_m - s.sonar.pose.position_m[2]; // r = H / d_z, needs H / d_z > 0
    const ShadeConstants c = shade_constants(s);
    const Material& mat = s.seafloor->material;
    // Linear intensities are taken relative to 10^(L_S/10) so that they stay in double's range.
    auto integrand = [&](double e, double dz) {
        const double r = H / dz, cos_inc = std::abs(dz);
        return std::exp((cell_echo_db(c, mat, r, cos_inc, std::cos(e) * pattern(e)) - c.source_level_db) *
                        kLn10Over10);
    };

    std::vector<double> E(size_t(N) * K, 0.0);
    tbb::parallel_for(0, N, [&](int i) {
        const double a_lo = grid->beam_starboard_edge_rad(i), pw = grid->beam_width_rad(i) / panels;
        std::vector<double> cuts;
        for (int p = 0; p < panels; ++p)
            for (int g = 0; g < 8; ++g) {
                const double a = a_lo + pw * (p + 0.5 + 0.5 * kGLx[g]), wa = 0.5 * pw * kGLw[g];
                // World z of the ray direction: d_z(e) = A cos e + B sin e = C cos(e - delta).
                const double A = R[0][2] * std::cos(a) + R[1][2] * std::sin(a), B = R[2][2];
                const double C = std::hypot(A, B), delta = std::atan2(B, A);
                cuts.assign({-phi / 2, phi / 2});
                auto add_roots = [&](double value) { // C cos(e - delta) = value
                    if (std::abs(value) > C) return;
                    const double base = std::acos(value / C);
                    for (double sgn : {-1.0, 1.0})
                        for (int n = -1; n <= 1; ++n) {
                            const double e = delta + sgn * base + 2 * kPi * n;
                            if (e > -phi / 2 && e < phi / 2) cuts.push_back(e);
                        }
                };
                add_roots(0.0); // horizon
                if (mat.mu >
                    0) // a specular lobe: cut around normal incidence (d_z extreme at e = delta, delta + pi)
                    for (double centre : {delta, delta + kPi, delta - kPi})
                        for (double f : {0.0, 0.25, 0.5, 1.0, 2.0, 4.0, 8.0})
                            for (double sgn : {-1.0, 1.0}) {
                                const double e = centre + sgn * f * deg2rad(mat.h_deg);
                                if (e > -phi / 2 && e < phi / 2) cuts.push_back(e);
                            }
                for (int k = 0; k <= K; ++k) add_roots(H / (r_min + k * dr));
                std::sort(cuts.begin(), cuts.end());
                for (size_t m = 0; m + 1 < cuts.size(); ++m) {
                    const double e0 = cuts[m], e1 = cuts[m + 1];
                    if (!(e1 > e0)) continue;
                    const double em = 0.5 * (e0 + e1), dzm = C * std::cos(em - delta);
                    if (!(H / dzm > 0)) continue;
                    const double rm = H / dzm;
                    if (rm < r_min || rm >= r_max) continue;
                    const int k = std::min(K - 1, int((rm - r_min) / dr));
                    double sum = 0;
                    for (int g2 = 0; g2 < 8; ++g2) {
                        const double e = em + 0.5 * (e1 - e0) * kGLx[g2];
                        sum += kGLw[g2] * integrand(e, C * std::cos(e - delta));
                    }
                    E[size_t(k) * N + i] += wa * 0.5 * (e1 - e0) * sum;
                }
            }
    });
    PolarImage img;
    img.bins = K, img.beams = N;
    img.level_db.resize(E.size());
    for (size_t n = 0; n < E.size(); ++n)
        img.level_db[n] = E[n] > 0 ? float(10 * std::log10(E[n]) + c.source_level_db - c.noise_level_db)
                                   : -std::numeric_limits<float>::infinity();
    return img;
}

ImageError compare_images(const PolarImage& img, const PolarImage& ref) {
    ImageError e;
    // Linear intensities relative to the reference's peak, so that the sums stay in range.
    double peak = -INFINITY;
    for (float v : ref.level_db) peak = std::max(peak, double(v));
    double num = 0, den = 0;
    std::vector<double> diffs;
    for (size_t n = 0; n < ref.level_db.size(); ++n) {
        const double a = img.level_db[n], b = ref.level_db[n];
        const bool ea = a > -INFINITY, eb = b > -INFINITY;
        const double lb = eb ? std::exp((b - peak) * kLn10Over10) : 0.0;
        const double la = a == b ? lb : ea ? std::exp((a - peak) * kLn10Over10) : 0.0;
        num += std::abs(la - lb), den += lb;
        if (eb) ++e.echoing_ref;
        if (eb && !ea) ++e.holes;
        if (ea && !eb) ++e.spurious;
        if (ea && eb) diffs.push_back(std::abs(a - b));
    }
    e.rel_l1 = den > 0 ? num / den : (num > 0 ? INFINITY : 0.0);
    if (!diffs.empty()) {
        auto q = [&](double f) {
            const size_t k = std::min(diffs.size() - 1, size_t(f * (diffs.size() - 1) + 0.5));
            std::nth_element(diffs.begin(), diffs.begin() + long(k), diffs.end());
            return diffs[k];
        };
        e.median_abs_db = q(0.5);
        e.p95_abs_db = q(0.95);
    }
    return e;
}

} // namespace sonarsim

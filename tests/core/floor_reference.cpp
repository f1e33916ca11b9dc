#include "floor_reference.hpp"

#include "support.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sonarsim::test {
namespace {

constexpr double kPi = 3.14159265358979323846;
double rad(double deg) {
    return deg * kPi / 180.0;
}

/// Angle wrapped into (-pi, pi].
double wrap(double x) {
    return std::remainder(x, 2 * kPi);
}

} // namespace

FloorSetup floor_setup(const SceneDesc& s) {
    if (!s.seafloor || !s.objects.empty())
        throw std::invalid_argument("floor_setup: floor-only scene needed");
    FloorSetup f{};
    f.height_m = s.sonar.pose.position_m[2] - s.seafloor->height_m;
    if (!(f.height_m > 0)) throw std::invalid_argument("floor_setup: sonar must be above the floor");
    // Third row of Rz(y) Ry(p) Rx(r): Rz leaves z alone, so it is (Ry Rx) row 2 = (-sp, cp sr, cp cr).
    const double r = rad(s.sonar.pose.orientation_deg[0]), p = rad(s.sonar.pose.orientation_deg[1]);
    f.rz[0] = -std::sin(p), f.rz[1] = std::cos(p) * std::sin(r), f.rz[2] = std::cos(p) * std::cos(r);
    f.theta = rad(s.sonar.azimuth_fov_deg), f.phi = rad(s.sonar.elevation_fov_deg);
    f.beams = s.sonar.beams, f.bins = s.sonar.range_bins;
    f.r_min = s.sonar.range_min_m, f.r_max = s.sonar.range_max_m, f.dr = (f.r_max - f.r_min) / f.bins;
    f.source_lin = std::pow(10.0, s.sonar.source_level_db / 10);
    const double fk = s.sonar.frequency_khz, t = s.water.temperature_c, d_km = s.water.depth_m / 1000;
    f.alpha = 0.00049 * fk * fk * std::exp(-(t / 27 + d_km / 17)) / 1000;
    const Material& m = s.seafloor->material;
    f.nu = std::pow(10.0, m.nu_db / 10), f.q = m.q, f.mu = m.mu, f.h_rad = rad(m.h_deg);
    return f;
}

double floor_integrand(const FloorSetup& f, double a, double e, double* range_m) {
    const double ce = std::cos(e);
    const double dz = f.rz[0] * ce * std::cos(a) + f.rz[1] * ce * std::sin(a) + f.rz[2] * std::sin(e);
    if (!(dz < 0)) {
        *range_m = INFINITY;
        return 0;
    }
    const double cos_inc = -dz, r = f.height_m / cos_inc;
    *range_m = r;
    double s_bs = f.nu * std::pow(cos_inc, f.q);
    if (f.mu > 0) {
        const double inc = std::acos(std::min(1.0, cos_inc));
        s_bs += f.mu * std::exp(-inc * inc / (2 * f.h_rad * f.h_rad));
    }
    // 10^((L_S - 2 (20 log r + alpha r) + L_BS) / 10) * r^2 / cos(inc) * cos(e)
    return f.source_lin * std::pow(10.0, -0.2 * f.alpha * r) * s_bs / (r * r * cos_inc) * ce;
}

std::vector<double> floor_reference_intensity(const SceneDesc& scene, int az_panels, int az_nodes,
                                              int el_nodes) {
    const FloorSetup f = floor_setup(scene);
    const GaussLegendre gl_a(az_nodes), gl_e(el_nodes);
    const int K = f.bins, N = f.beams;
    std::vector<double> edges(size_t(K) + 1);
    for (int k = 0; k <= K; ++k) edges[size_t(k)] = f.r_min + k * f.dr;
    std::vector<double> E(size_t(K) * size_t(N), 0.0);
    const double e_top = f.phi / 2, e_bot = -f.phi / 2, beam_w = f.theta / N;
    std::vector<double> cuts;

    // Adds weight * (elevation integral at azimuth a, split by bin) into beam i's column.
    auto elevation = [&](double a, double weight, int i) {
        // d_z(e) = A cos e + B sin e = C cos(e - delta)
        const double A = f.rz[0] * std::cos(a) + f.rz[1] * std::sin(a), B = f.rz[2];
        const double C = std::hypot(A, B), delta = std::atan2(B, A);
        cuts.assign({e_bot, e_top});
        // Only edges within the ranges this azimuth's elevation fan spans can cut it: -d_z is largest at an
        // end of [e_bot, e_top] or at e = delta + pi (most downward) when that lies inside.
        double down_hi =
            std::max(-A * std::cos(e_bot) - B * std::sin(e_bot), -A * std::cos(e_top) - B * std::sin(e_top));
        const double e_down = wrap(delta + kPi);
        if (e_down > e_bot && e_down < e_top) down_hi = C;
        if (!(down_hi > 0)) return; // the whole fan looks above the horizon
        const int k_first = std::max(0, int(std::floor((f.height_m / down_hi - f.r_min) / f.dr)));
        for (int k = k_first; k <= K; ++k) {
            const double rho = edges[size_t(k)];
            const double g = -f.height_m / (rho * C); // r(e) = rho  <=>  cos(e - delta) = g
            if (std::abs(g) > 1) continue;
            for (double sgn : {-1.0, 1.0}) {
                const double e = wrap(delta + sgn * std::acos(g));
                if (e > e_bot && e < e_top) cuts.push_back(e);
            }
        }
        std::sort(cuts.begin(), cuts.end());
        for (size_t n = 0; n + 1 < cuts.size(); ++n) {
            const double e0 = cuts[n], e1 = cuts[n + 1];
            if (!(e1 > e0)) continue;
            double r_mid;
            floor_integrand(f, a, 0.5 * (e0 + e1), &r_mid);
            if (!(r_mid >= f.r_min && r_mid < f.r_max)) continue;
            const int k = std::min(K - 1, int(std::floor((r_mid - f.r_min) / f.dr)));
            const double v = gl_e.integrate(e0, e1, [&](double e) {
                double r;
                return floor_integrand(f, a, e, &r);
            });
            E[size_t(k) * N + size_t(i)] += weight * v;
        }
    };

    // Azimuths at which r(a, e_lim) = rho: d_z = ce (rz0 cos a + rz1 sin a) + rz2 se = -H / rho.
    const double W = std::hypot(f.rz[0], f.rz[1]), gamma = std::atan2(f.rz[1], f.rz[0]);
    for (int i = 0; i < N; ++i) {
        const double a_c = f.theta / 2 - (i + 0.5) * beam_w, a_lo = a_c - beam_w / 2, a_hi = a_c + beam_w / 2;
        std::vector<double> brk = {a_lo, a_hi};
        for (double e : {e_bot, e_top})
            for (double rho : edges) {
                const double g = (-f.height_m / rho - f.rz[2] * std::sin(e)) / (std::cos(e) * W);
                if (W == 0 || std::abs(g) > 1) continue;
                for (double sgn : {-1.0, 1.0}) {
                    const double a = wrap(gamma + sgn * std::acos(g));
                    if (a > a_lo && a < a_hi) brk.push_back(a);
                }
            }
        std::sort(brk.begin(), brk.end());
        for (size_t n = 0; n + 1 < brk.size(); ++n) {
            const double h = (brk[n + 1] - brk[n]) / az_panels;
            if (!(h > 0)) continue;
            for (int p = 0; p < az_panels; ++p) {
                const double c = brk[n] + (p + 0.5) * h;
                for (size_t j = 0; j < gl_a.x.size(); ++j)
                    elevation(c + 0.5 * h * gl_a.x[j], 0.5 * h * gl_a.w[j], i);
            }
        }
    }
    return E;
}

std::vector<double> floor_bruteforce_beam(const SceneDesc& scene, int beam, int na, int ne) {
    const FloorSetup f = floor_setup(scene);
    std::vector<double> E(size_t(f.bins), 0.0);
    const double beam_w = f.theta / f.beams, a_lo = f.theta / 2 - (beam + 1) * beam_w;
    const double da = beam_w / na, de = f.phi / ne;
    for (int ia = 0; ia < na; ++ia) {
        const double a = a_lo + (ia + 0.5) * da;
        for (int ie = 0; ie < ne; ++ie) {
            double r;
            const double v = floor_integrand(f, a, -f.phi / 2 + (ie + 0.5) * de, &r);
            if (v > 0 && r >= f.r_min && r < f.r_max) {
                const int k = std::min(f.bins - 1, int(std::floor((r - f.r_min) / f.dr)));
                E[size_t(k)] += v * da * de;
            }
        }
    }
    return E;
}

} // namespace sonarsim::test

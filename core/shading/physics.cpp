#include "core/shading/physics.hpp"

#include "core/data/pose.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sonarsim {

namespace {
constexpr double kNegInf = -std::numeric_limits<double>::infinity();
} // namespace

double absorption_db_per_m(double f_khz, double t_c, double depth_m) {
    return 0.00049 * f_khz * f_khz * std::exp(-(t_c / 27.0 + depth_m / 1000.0 / 17.0)) / 1000.0;
}

double sound_speed_m_s(double t, double z) {
    const double salinity = 35;
    return 1449.2 + 4.6 * t - 0.055 * t * t + 0.00029 * t * t * t + (1.34 - 0.01 * t) * (salinity - 35) +
           0.016 * z;
}

double transmission_loss_db(double r, double alpha) {
    return 20.0 * std::log10(r) + alpha * r;
}

double backscatter_db(const Material& m, double cos_inc) {
    if (!(cos_inc > 0)) return kNegInf;
    cos_inc = std::min(cos_inc, 1.0);
    // Natural-log terms; the sum is done as log-sum-exp so no term underflows on its own.
    const double lambert = m.nu_db * kLn10Over10 + (m.q == 0 ? 0.0 : m.q * std::log(cos_inc));
    if (!(m.mu > 0)) return lambert / kLn10Over10;
    double spec = kNegInf;
    if (m.mu > 0) {
        const double theta = std::acos(cos_inc), h = deg2rad(m.h_deg);
        spec = std::log(m.mu) - theta * theta / (2 * h * h);
    }
    const double hi = std::max(lambert, spec), lo = std::min(lambert, spec);
    if (hi == kNegInf) return kNegInf;
    return (hi + std::log1p(std::exp(lo - hi))) / kLn10Over10;
}

ShadeConstants shade_constants(const SceneDesc& s) {
    return {s.sonar.source_level_db, s.sonar.noise_level_db,
            absorption_db_per_m(s.sonar.frequency_khz, s.water.temperature_c, s.water.depth_m),
            2 * kPi * s.sonar.frequency_khz * 1e3 / sound_speed_m_s(s.water.temperature_c, s.water.depth_m)};
}

double cell_echo_db(const ShadeConstants& c, const Material& m, double r, double cos_inc, double d_omega) {
    if (!(r > 0) || !(cos_inc > 0) || !(d_omega > 0)) return kNegInf;
    cos_inc = std::min(cos_inc, 1.0);
    // -2 L_TL + 10 log10(r^2 dOmega / cos) = -20 log10 r - 2 alpha r + 10 log10(dOmega / cos): spreading and
    // area combined, so it stays finite as r -> 0. Without a specular term L_BS folds in as nu + q 10 log10
    // cos.
    const double base = c.source_level_db - 2.0 * c.alpha_db_per_m * r;
    if (m.mu == 0) {
        // One logarithm for the usual exponents (Lambert's q = 2, and q = 1), two for any other.
        const double area = d_omega / (r * r);
        if (m.q == 2) return base + m.nu_db + std::log(area * cos_inc) / kLn10Over10;
        if (m.q == 1) return base + m.nu_db + std::log(area) / kLn10Over10;
        return base + m.nu_db + (std::log(area) + (m.q - 1.0) * std::log(cos_inc)) / kLn10Over10;
    }
    return base + backscatter_db(m, cos_inc) + 10.0 * std::log10(d_omega / (cos_inc * r * r));
}

} // namespace sonarsim

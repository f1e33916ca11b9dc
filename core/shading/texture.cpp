#include "core/shading/texture.hpp"

#include "core/base/pose.hpp"
#include "core/base/units.hpp"
#include "core/geometry/geometry.hpp"

#include <array>
#include <cmath>

namespace sonarsim {
namespace {

/// lowbias32 (Chris Wellons' hash prospector): a full-avalanche 32-bit mix.
std::uint32_t mix(std::uint32_t h) {
    h ^= h >> 16, h *= 0x7feb352du, h ^= h >> 15, h *= 0x846ca68bu, h ^= h >> 16;
    return h;
}

std::uint32_t mix(std::uint32_t seed, std::uint32_t v) {
    return mix(seed ^ (v + 0x9e3779b9u + (seed << 6) + (seed >> 2)));
}

double uniform01(std::uint32_t h) {
    return (double(h) + 0.5) / 4294967296.0;
}

/// 4096 standard normal quantiles Phi^-1((i + 1/2)/4096), scaled to exactly zero mean and unit variance:
/// a lattice value is table[hash >> 20].
constexpr int kTableBits = 12;
const std::array<double, 1 << kTableBits>& normal_table() {
    static const auto table = [] {
        std::array<double, 1 << kTableBits> t{};
        double sum2 = 0;
        for (size_t i = 0; i < t.size(); ++i) {
            const double p = (double(i) + 0.5) / double(t.size());
            double lo = -10, hi = 10; // Phi(x) = erfc(-x / sqrt 2) / 2 is increasing: bisect
            for (int it = 0; it < 80; ++it) {
                const double mid = 0.5 * (lo + hi);
                (0.5 * std::erfc(-mid / std::sqrt(2.0)) < p ? lo : hi) = mid;
            }
            t[i] = 0.5 * (lo + hi), sum2 += t[i] * t[i];
        }
        for (double& v : t) v /= std::sqrt(sum2 / double(t.size())); // symmetric: the mean is 0
        return t;
    }();
    return table;
}

/// A uniformly distributed rotation from a seed (Shoemake's quaternion from three uniforms).
glm::dmat3 random_rotation(std::uint32_t seed) {
    const double u1 = uniform01(mix(seed, 1)), u2 = 2 * kPi * uniform01(mix(seed, 2)),
                 u3 = 2 * kPi * uniform01(mix(seed, 3));
    const double a = std::sqrt(1 - u1), b = std::sqrt(u1);
    const double w = a * std::sin(u2), x = a * std::cos(u2), y = b * std::sin(u3), z = b * std::cos(u3);
    return glm::dmat3(1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y), // column 0
                      2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x), // column 1
                      2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y));
}

/// Smoothstep weights of the lower and upper lattice node, normalised so their squares sum to 1.
inline void weights(double f, double& w0, double& w1) {
    const double s = f * f * (3 - 2 * f), n = 1.0 / std::sqrt((1 - s) * (1 - s) + s * s);
    w0 = (1 - s) * n, w1 = s * n;
}

} // namespace

GaussianField::GaussianField(double correlation_m, std::uint32_t seed, const glm::dmat3& to_frame,
                             const glm::dvec3& frame_offset_m)
    : seed_(mix(seed)) {
    const double per_m = 1.0 / (kSpacingPerCorrelation * correlation_m); // lattice spacings per metre
    const glm::dmat3 L = random_rotation(mix(seed, 0x5eed));
    m_ = per_m * (L * to_frame), b_ = per_m * (L * frame_offset_m);
}

double GaussianField::operator()(const glm::dvec3& p) const {
    const glm::dvec3 u = m_ * p + b_;
    const glm::dvec3 fl = glm::floor(u);
    double w[3][2];
    for (int a = 0; a < 3; ++a) weights(u[a] - fl[a], w[a][0], w[a][1]);
    const auto& table = normal_table();
    const std::uint32_t ix = std::uint32_t(std::int64_t(fl.x)), iy = std::uint32_t(std::int64_t(fl.y)),
                        iz = std::uint32_t(std::int64_t(fl.z));
    double g = 0;
    for (std::uint32_t dx = 0; dx < 2; ++dx) {
        const std::uint32_t hx = mix(seed_, ix + dx);
        for (std::uint32_t dy = 0; dy < 2; ++dy) {
            const std::uint32_t hy = mix(hx, iy + dy);
            const double wxy = w[0][dx] * w[1][dy];
            g += wxy * (w[2][0] * table[mix(hy, iz) >> (32 - kTableBits)] +
                        w[2][1] * table[mix(hy, iz + 1) >> (32 - kTableBits)]);
        }
    }
    return g;
}

double MaterialTexture::level_db(const glm::dvec3& p) const {
    double l = mean_offset_db;
    if (rms_db > 0) l += rms_db * level(p);
    if (ripple_db > 0) l += ripple_db * std::cos(glm::dot(ripple_k, p) + ripple_phase);
    return l;
}

double MaterialTexture::facet_cos(const glm::dvec3& p, double cos_incidence) const {
    const double theta = std::acos(std::min(1.0, cos_incidence));
    return std::cos(theta + slope_rms_rad * slope(p));
}

MaterialTexture material_texture(const Material& m, const glm::dmat3& R, const glm::dvec3& t,
                                 std::uint32_t seed) {
    MaterialTexture x;
    const glm::dmat3 Rt = glm::transpose(R);
    const glm::dvec3 offset = -(Rt * t);
    x.rms_db = m.texture_rms_db, x.ripple_db = m.ripple_amplitude_db;
    x.level_on = x.rms_db > 0 || x.ripple_db > 0;
    // E[10^(L/10)] = 1: for L = sigma g, g ~ N(0, 1), E[exp(beta sigma g)] = exp(beta^2 sigma^2 / 2), beta =
    // ln10/10; for L = A cos(phase), phase uniform, E[exp(beta A cos)] = I0(beta A). Subtract both in dB.
    x.mean_offset_db = -(x.rms_db * x.rms_db * kLn10Over10 / 2 +
                         10 * std::log10(std::cyl_bessel_i(0.0, kLn10Over10 * x.ripple_db)));
    if (x.rms_db > 0) x.level = GaussianField(m.texture_correlation_m, mix(seed, 1), Rt, offset);
    if (x.ripple_db > 0) {
        const double k = 2 * kPi / m.ripple_wavelength_m, d = deg2rad(m.ripple_direction_deg);
        x.ripple_k = R * glm::dvec3(k * std::cos(d), k * std::sin(d), 0);
        x.ripple_phase = 2 * kPi * uniform01(mix(seed, 3)) - glm::dot(x.ripple_k, t);
    }
    x.slope_rms_rad = deg2rad(m.slope_rms_deg);
    x.slope_on = x.slope_rms_rad > 0;
    if (x.slope_on) x.slope = GaussianField(m.texture_correlation_m, mix(seed, 2), Rt, offset);
    return x;
}

SceneTexture::SceneTexture(const SceneDesc& s) {
    const glm::dmat3 I(1.0);
    const glm::dvec3 O(0.0);
    by_index_.push_back(s.seafloor ? material_texture(s.seafloor->material, I, O, 0) : MaterialTexture{});
    for (size_t i = 0; i < s.objects.size(); ++i) {
        const ObjectDesc& o = s.objects[i];
        by_index_.push_back(material_texture(o.material, rotation_matrix(o.orientation_deg),
                                             to_glm(o.position_m), std::uint32_t(i + 1)));
    }
    by_index_.push_back(material_texture(s.water.surface_material, I, O, 0xffffu));
    for (const MaterialTexture& t : by_index_) any_ = any_ || t.level_on || t.slope_on;
}

const MaterialTexture& SceneTexture::of(unsigned m) const {
    if (m == kSurfaceMaterial) return by_index_.back();
    return by_index_.at(m);
}

} // namespace sonarsim

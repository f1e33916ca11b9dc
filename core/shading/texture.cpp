#include "core/shading/texture.hpp"

#include "core/data/pose.hpp"
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

/// Smoothstep: the upper node's weight before normalisation.
inline double smooth(double f) {
    return f * f * (3 - 2 * f);
}

} // namespace

GaussianField::GaussianField(double correlation_m, std::uint32_t seed, const glm::dmat3& to_frame,
                             const glm::dvec3& frame_offset_m) {
    const double per_m = 1.0 / (kSpacingPerCorrelation * correlation_m); // lattice spacings per metre
    for (std::uint32_t n = 0; n < 2; ++n) {
        Lattice& l = lattice_[n];
        const std::uint32_t s = mix(seed, 0x5eed + n);
        const glm::dmat3 L = random_rotation(s);
        const glm::dvec3 shift(uniform01(mix(s, 4)), uniform01(mix(s, 5)), uniform01(mix(s, 6)));
        l.m = per_m * (L * to_frame), l.b = per_m * (L * frame_offset_m) + shift, l.seed = mix(s, 7);
    }
}

glm::dvec2 GaussianField::operator()(const glm::dvec3& p) const {
    return (lattice_[0](p) + lattice_[1](p)) * 0.70710678118654752; // independent: variance 1
}

glm::dvec2 GaussianField::Lattice::operator()(const glm::dvec3& p) const {
    const glm::dvec3 u = m * p + b, fl = glm::floor(u);
    const double sx = smooth(u.x - fl.x), sy = smooth(u.y - fl.y), sz = smooth(u.z - fl.z);
    // The node hash: the lattice point's coordinates times odd 64-bit constants (no two points within ~2
    // million spacings of each other share the sum), folded to 32 bits with the seed, then mixed.
    constexpr std::uint64_t kX = 0x9e3779b97f4a7c15ull, kY = 0xc2b2ae3d27d4eb4full,
                            kZ = 0x165667b19e3779f9ull;
    const std::uint64_t X = std::uint64_t(std::int64_t(fl.x)) * kX,
                        Y = std::uint64_t(std::int64_t(fl.y)) * kY,
                        Z = std::uint64_t(std::int64_t(fl.z)) * kZ;
    const auto& table = normal_table();
    auto value = [&](std::uint64_t h) { // a node's two values: the hash's top and bottom bits
        const std::uint32_t m = mix(std::uint32_t(h ^ (h >> 32)) ^ seed);
        return glm::dvec2(table[m >> (32 - kTableBits)], table[m & ((1u << kTableBits) - 1)]);
    };
    const double z0 = 1 - sz, z1 = sz, y0 = 1 - sy, y1 = sy, x0 = 1 - sx, x1 = sx;
    const std::uint64_t a = X + Y + Z;
    const glm::dvec2 g = x0 * (y0 * (z0 * value(a) + z1 * value(a + kZ)) +
                               y1 * (z0 * value(a + kY) + z1 * value(a + kY + kZ))) +
                         x1 * (y0 * (z0 * value(a + kX) + z1 * value(a + kX + kZ)) +
                               y1 * (z0 * value(a + kX + kY) + z1 * value(a + kX + kY + kZ)));
    // Unit variance: the squared weights are separable, (x0^2 + x1^2)(y0^2 + y1^2)(z0^2 + z1^2).
    return g / std::sqrt((x0 * x0 + x1 * x1) * (y0 * y0 + y1 * y1) * (z0 * z0 + z1 * z1));
}

MaterialTexture::Sample MaterialTexture::at(const glm::dvec3& p) const {
    Sample r;
    const glm::dvec2 g = rms_db > 0 || slope_on ? field(p) : glm::dvec2(0.0);
    r.level_db = mean_offset_db + rms_db * g.x;
    if (ripple_db > 0) r.level_db += ripple_db * std::cos(glm::dot(ripple_k, p) + ripple_phase);
    r.tilt_rad = slope_rms_rad * g.y;
    return r;
}

double MaterialTexture::facet_cos(const glm::dvec3& p, double cos_incidence) const {
    const double c = std::min(1.0, cos_incidence), d = at(p).tilt_rad;
    return c * std::cos(d) - std::sqrt(1 - c * c) * std::sin(d); // cos(theta + delta)
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
    if (x.ripple_db > 0) {
        const double k = 2 * kPi / m.ripple_wavelength_m, d = deg2rad(m.ripple_direction_deg);
        x.ripple_k = R * glm::dvec3(k * std::cos(d), k * std::sin(d), 0);
        x.ripple_phase = 2 * kPi * uniform01(mix(seed, 3)) - glm::dot(x.ripple_k, t);
    }
    x.slope_rms_rad = deg2rad(m.slope_rms_deg);
    x.slope_on = x.slope_rms_rad > 0;
    if (x.rms_db > 0 || x.slope_on)
        x.field = GaussianField(m.texture_correlation_m, mix(seed, 1), Rt, offset);
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

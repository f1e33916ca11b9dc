#include "core/shading/shade.hpp"

#include "core/shading/footprint.hpp"
#include "core/shading/log_sum.hpp"
#include "core/geometry/geometry.hpp"
#include "core/data/pose.hpp"
#include "core/grid/sensor_patterns.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sonarsim {
namespace {

constexpr double kNegInf = -std::numeric_limits<double>::infinity();

} // namespace

double cell_fraction_in(const Cell& c, EchoBinning binning, double r0, double r1) {
    if (binning == EchoBinning::Point) return (c.range_m >= r0 && c.range_m < r1) ? 1.0 : 0.0;
    const detail::Footprint f = detail::footprint_of(c);
    if (f.p + f.q <= 1e-9 * (r1 - r0)) return (f.lo >= r0 && f.lo < r1) ? 1.0 : 0.0;
    return f.cdf(r1) - f.cdf(r0);
}

double reflection_gain_db(const ShadeConstants& k, const SceneDesc& s, unsigned m, double cos_inc) {
    if (m != kSurfaceMaterial) return -material_of(s, m).reflection_db;
    // Kirchhoff (Eckart): the coherent amplitude is exp(-2 k^2 sigma^2 cos^2), so |R|^2 = exp(-g^2) with g
    // the Rayleigh parameter 2 k sigma cos.
    const double g = 2 * k.wavenumber_rad_per_m * s.water.surface_roughness_m * cos_inc;
    return -g * g / kLn10Over10; // 10 log10 exp(-g^2)
}

double ghost_echo_db(const ShadeConstants& k, const SceneDesc& s, const GhostCell& g) {
    const Cell& c = g.cell;
    const double cos_in = std::min(1.0, double(c.cos_incidence)),
                 cos_out = std::min(1.0, double(g.cos_other));
    if (!(c.range_m > 0) || !(cos_in > 0) || !(c.solid_angle_sr > 0) || !(g.other_leg_m > 0)) return kNegInf;
    if (g.mixed() && !(cos_out > 0)) return kNegInf;
    const Material& m = material_of(s, c.material);
    double refl = 0;
    for (int j = 0; j < g.mirrors(); ++j)
        refl += (g.mixed() ? 1 : 2) * reflection_gain_db(k, s, g.mirror_material[j], g.mirror_cos[j]);
    const double leg_m = g.other_leg_m;
    const double base_db = k.source_level_db - 2.0 * k.alpha_db_per_m * c.range_m + refl;
    // 10 log10(dOmega / (cos_in leg^2)) and Lambert's cosines as one logarithm for q = 0, 1, 2: a double
    // path's cos_in^q, a mixed path's (cos_in cos_out)^(q/2).
    const double area = c.solid_angle_sr / (leg_m * leg_m);
    if (m.mu == 0 && (m.q == 0 || m.q == 1 || m.q == 2)) {
        double cosines = 1 / cos_in; // q = 0
        if (m.q == 2) cosines = g.mixed() ? cos_out : cos_in;
        if (m.q == 1) cosines = g.mixed() ? std::sqrt(cos_out / cos_in) : 1.0;
        return base_db + m.nu_db + std::log(area * cosines) / kLn10Over10;
    }
    const double bs = g.mixed() ? m.nu_db + 0.5 * m.q * std::log(cos_in * cos_out) / kLn10Over10
                                : backscatter_db(m, cos_in);
    return base_db + std::log(area / cos_in) / kLn10Over10 + bs;
}

BeamContributions::BeamContributions(const TraceResult& hits, int beam)
    : cells_(hits.cells[size_t(beam)]),
      ghosts_(size_t(beam) < hits.ghosts.size() ? &hits.ghosts[size_t(beam)] : nullptr) {}

namespace {

/// A contribution's level [dB] with its material's texture: the level field at its point and, on a direct
/// cell, the backscatter at the facet's incidence theta' over the mean plane's area: cell_echo_db(theta') +
/// 10 log10(cos theta' / cos theta).
double textured_db(const ShadeConstants& k, const SceneDesc& s, const SceneTexture& texture, const Cell& c,
                   const GhostCell* g) {
    const MaterialTexture& t = texture.of(c.material);
    const MaterialTexture::Sample x = t.at(glm::dvec3(c.point_m));
    if (g) return ghost_echo_db(k, s, *g) + x.level_db;
    const Material& m = material_of(s, c.material);
    if (!t.slope_on) return cell_echo_db(k, m, c.range_m, c.cos_incidence, c.solid_angle_sr) + x.level_db;
    if (!(c.cos_incidence > 0)) return kNegInf;
    const double cos_mean = std::min(1.0, double(c.cos_incidence)),
                 cos_facet = cos_mean * std::cos(x.tilt_rad) -
                             std::sqrt(1 - cos_mean * cos_mean) * std::sin(x.tilt_rad);
    if (!(cos_facet > 0)) return kNegInf; // the facet faces away
    return cell_echo_db(k, m, c.range_m, cos_facet, c.solid_angle_sr) +
           std::log(cos_facet / cos_mean) / kLn10Over10 + x.level_db;
}

} // namespace

double contribution_levels(const BeamContributions& beam, const SceneDesc& s, const ShadeConstants& k,
                           std::vector<double>& x, const SceneTexture* texture) {
    x.resize(beam.size());
    double x_max = kNegInf;
    for (size_t n = 0; n < beam.size(); ++n) {
        const Cell& c = beam[n];
        const GhostCell* g = beam.ghost(n);
        if (texture)
            x[n] = textured_db(k, s, *texture, c, g) * kLn10Over10;
        else
            x[n] = (g ? ghost_echo_db(k, s, *g)
                      : cell_echo_db(k, material_of(s, c.material), c.range_m, c.cos_incidence,
                                     c.solid_angle_sr)) *
                   kLn10Over10;
        if (std::isnan(x[n])) x[n] = kNegInf;
        x_max = std::max(x_max, x[n]);
    }
    return x_max;
}

} // namespace sonarsim

// Seabed texture: per material, a seeded random field of backscatter level and of small-scale slope, fixed to
// the surface it lies on (the seafloor's and the water surface's to the world, an object's to the object), so
// it moves with the world and stays put while nothing moves. Formulas in docs/model.md ("Seabed texture").
#pragma once
#include "core/scene/scene.hpp"

#include <glm/glm.hpp>
#include <vector>

namespace sonarsim {

/// A stationary random field with standard normal marginals at every point and an autocorrelation that falls
/// to 1/e at `correlation_m` (along any direction within a few per cent): Gaussian values on a seeded,
/// randomly rotated cubic lattice, interpolated with smoothstep weights normalised to unit variance. The
/// normalised weights are separable, so the autocorrelation is the product of one 1D function per axis.
class GaussianField {
  public:
    GaussianField() = default;
    /// `to_frame`: world point -> the surface's frame [m] (rotation R^T, then -R^T t).
    GaussianField(double correlation_m, std::uint32_t seed, const glm::dmat3& to_frame,
                  const glm::dvec3& frame_offset_m);
    /// g(point), point in world coordinates [m].
    double operator()(const glm::dvec3& world_m) const;

    /// The lattice spacing per metre of correlation length: the 1/e lag of the 1D autocorrelation of
    /// smoothstep-interpolated unit-variance lattice values is 0.8237 spacings.
    static constexpr double kSpacingPerCorrelation = 1.0 / 0.8237;

  private:
    glm::dmat3 m_{1.0};
    glm::dvec3 b_{0.0};
    std::uint32_t seed_ = 0;
};

/// One material's texture, ready to evaluate.
struct MaterialTexture {
    bool level_on = false, slope_on = false;
    double rms_db = 0;          ///< sigma: rms of the random level [dB]
    double ripple_db = 0;       ///< A: peak amplitude of the ripples' level [dB]
    double mean_offset_db = 0;  ///< -(sigma^2 ln10/20 + 10 log10 I0(A ln10/10)): keeps the linear mean
    glm::dvec3 ripple_k{0.0};   ///< ripples' wave vector in world coordinates [rad/m]
    double ripple_phase = 0;    ///< its phase at the world origin [rad]
    double slope_rms_rad = 0;   ///< rms of the facet tilt in the plane of incidence [rad]
    GaussianField level, slope; ///< independent fields (different seeds)

    /// Level offset at a world point [dB]; unit mean in linear intensity over the surface.
    double level_db(const glm::dvec3& world_m) const;
    /// cos of the incidence on the tilted facet at a world point: cos(theta + sigma_s h(x)).
    double facet_cos(const glm::dvec3& world_m, double cos_incidence) const;
};

/// The textures of one scene's materials; none() when no material has one on (then shading skips it all).
class SceneTexture {
  public:
    explicit SceneTexture(const SceneDesc& scene);
    bool none() const { return !any_; }
    /// The texture of material index m (kFloorMaterial, kSurfaceMaterial or object index + 1).
    const MaterialTexture& of(unsigned material) const;

  private:
    std::vector<MaterialTexture> by_index_; ///< [0]: floor, [i]: object i - 1, back(): the water surface
    bool any_ = false;
};

/// Builds one material's texture on a surface whose frame is world = R x + t (`seed` tells surfaces apart).
MaterialTexture material_texture(const Material& m, const glm::dmat3& R, const glm::dvec3& t,
                                 std::uint32_t seed);

} // namespace sonarsim

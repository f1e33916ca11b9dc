// Seabed texture: per material, a seeded random field of backscatter level and of small-scale slope, fixed to
// the surface it lies on (the seafloor's and the water surface's to the world, an object's to the object), so
// it moves with the world and stays put while nothing moves. Formulas in docs/model.md ("Seabed texture").
#pragma once
#include "core/data/scene.hpp"

#include <glm/glm.hpp>
#include <vector>

namespace sonarsim {

/// Two independent stationary random fields (the level's and the slope's, one lattice walk for both) with
/// standard normal marginals at every point and an autocorrelation that falls
/// to 1/e at `correlation_m` (along any direction within a few per cent): the sum, over sqrt 2, of two
/// independent lattices, each of Gaussian values on a seeded, randomly rotated and shifted cubic lattice,
/// interpolated with smoothstep weights normalised to unit variance (separable: each lattice's
/// autocorrelation is the product of one 1D function per axis). Two lattices hide each one's nodes.
class GaussianField {
  public:
    GaussianField() = default;
    /// `to_frame`: world point -> the surface's frame [m] (rotation R^T, then -R^T t).
    GaussianField(double correlation_m, std::uint32_t seed, const glm::dmat3& to_frame,
                  const glm::dvec3& frame_offset_m);
    /// (g1, g2) at a world point [m]: two independent fields (each node holds two values).
    glm::dvec2 operator()(const glm::dvec3& world_m) const;

    /// The lattice spacing per metre of correlation length: the 1/e lag of the 1D autocorrelation of
    /// smoothstep-interpolated unit-variance lattice values is 0.8237 spacings.
    static constexpr double kSpacingPerCorrelation = 1.0 / 0.8237;

  private:
    struct Lattice {
        glm::dmat3 m{1.0}; ///< world -> lattice coordinates
        glm::dvec3 b{0.0};
        std::uint32_t seed = 0;
        glm::dvec2 operator()(const glm::dvec3& p) const;
    };
    Lattice lattice_[2];
};

/// One material's texture, ready to evaluate.
struct MaterialTexture {
    bool level_on = false, slope_on = false;
    double rms_db = 0;         ///< sigma: rms of the random level [dB]
    double ripple_db = 0;      ///< A: peak amplitude of the ripples' level [dB]
    double mean_offset_db = 0; ///< -(sigma^2 ln10/20 + 10 log10 I0(A ln10/10)): keeps the linear mean
    glm::dvec3 ripple_k{0.0};  ///< ripples' wave vector in world coordinates [rad/m]
    double ripple_phase = 0;   ///< its phase at the world origin [rad]
    double slope_rms_rad = 0;  ///< rms of the facet tilt in the plane of incidence [rad]
    GaussianField field;       ///< g1: the level's, g2: the slope's

    /// The texture at a world point: its level offset [dB] (unit mean in linear intensity over the surface)
    /// and the facet's tilt delta [rad] (cos of the facet's incidence: cos(theta + delta)).
    struct Sample {
        double level_db = 0, tilt_rad = 0;
    };
    Sample at(const glm::dvec3& world_m) const;
    double level_db(const glm::dvec3& world_m) const { return at(world_m).level_db; }
    /// cos(theta + delta) at a world point.
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

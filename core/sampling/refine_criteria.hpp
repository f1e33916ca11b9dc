// Adaptive sampling: when a pair of neighbouring cells, or one cell alone, must be split. Pure decisions on
// the cells' fields (hits, levels, footprints) against the scene's tolerance and the base grid's image: no
// ray is traced here (see core/sampling/README.md, "Adaptive sampling").
#pragma once
#include "core/sampling/adaptive_node.hpp"
#include "core/shading/physics.hpp"

#include <vector>

namespace sonarsim::adaptive {

/// The ray along the shared edge of two neighbouring cells, computed only when a criterion needs it: the
/// azimuth, and the elevation as an angle or (evaluated on demand) in radians.
struct EdgeRay {
    const Angle& azimuth;
    double elevation_rad = 0;
    const Angle* elevation = nullptr; ///< when given, used instead of elevation_rad
    /// With elevation_rad: the cell whose lower edge it is (centre angle and width), for a cheap
    /// approximate direction (dir_near) that decides most tests without a sine or cosine.
    const Angle* below = nullptr;
    double below_width = 0;
    glm::dvec3 dir(const detail::RayFrame& frame) const {
        return elevation ? frame.dir(azimuth, *elevation) : frame.dir(azimuth, Angle(elevation_rad));
    }
    /// dir() or a direction within 1e-14 of it (false: none, take dir()).
    bool dir_near(const detail::RayFrame& frame, glm::dvec3& d) const {
        if (elevation) return d = frame.dir(azimuth, *elevation), true;
        if (!below) return false;
        const Angle lower(elevation_rad, *below, detail::half_angle(below_width), -1);
        return d = frame.dir(azimuth, lower), true;
    }
};

/// What may_be_significant adds to its bound [dB] for the rounding of its two logarithms (below 1e-12 dB).
constexpr double kBoundMarginDb = 1e-6;

class RefineCriteria {
  public:
    /// `frame` must outlive the criteria; `multipath`: the nodes carry continuations to compare.
    RefineCriteria(const SceneDesc& scene, const detail::RayFrame& frame, bool multipath);

    /// Whether the cells of neighbours x (in column cx) and y (in cy) must be split: one misses, a surface
    /// edge lies between them, their levels step, or (grazing) their echo per metre of range steps; each
    /// only where the error it can cause is significant against the base image (base_db).
    bool discontinuous(const Node& x, const Column& cx, const Node& y, const Column& cy,
                       const EdgeRay& edge) const;

    /// discontinuous() for x and the next cell below it, y, in column c at azimuth a (across the edge
    /// between them): whether elevation refinement splits that pair.
    bool splits_pair(const Node& x, const Node& y, const Column& c, const Angle& a) const {
        return discontinuous(x, c, y, c, EdgeRay{a, x.angle.rad - x.de / 2, nullptr, &x.angle, x.de});
    }

    /// Whether the integrand is not smooth between neighbouring cells x and y in one column: one misses, a
    /// surface edge lies between them, or their levels step (by the steps of kSmoothToleranceDb where the
    /// tolerance is looser), and with multipath the same for their continuations (discontinuous() without
    /// the significance test). The error estimate takes a merged triple without such a step to converge
    /// in second order.
    bool edge_between(const Node& x, const Node& y, const EdgeRay& edge) const;

    /// A cell that must split on its own: absorption across its footprint, a specular lobe narrower than
    /// the cell centred inside it, or a plane horizon inside it. `a`: the column's azimuth.
    bool needs_split_alone(const Node& n, const Angle& a) const;

    /// A specular lobe whose azimuth falls inside the beam [a_lo, a_hi] and is narrower than its columns.
    bool specular_in_azimuth(const Node& n, double a_lo, double a_hi, double da) const;

    /// Absorption alone changes the echo by more than the range-spreading threshold across the column's
    /// azimuth width; `a`: the column's azimuth (c.a) as an angle.
    bool absorbed_across_azimuth(const Node& n, const Column& c, const Angle& a) const;

    /// Whether an error of a fraction f of node n's echo (in column c) is significant against the base image
    /// (see worth_refining; always with an empty base image).
    bool significant(const Node& n, const Column& c, double f) const;
    /// False only where significant(n, c, f) is false for every f <= 1/2 (the most a step can cost a cell):
    /// a bound from the node's echo per metre, with no logarithm of its own but one of the column width.
    bool may_be_significant(const Node& n, const Column& c) const;

    const SceneDesc& scene() const { return s_; }
    /// The relative error per bin the tolerance allows, over kErrorsPerBin [dB].
    double tolerance_per_bin_db() const { return tol_rel_db_; }
    const ShadeConstants& constants() const { return k_; }
    double bin_m() const { return bin_m_; }

    /// The base grid's image: [beam * range_bins + bin], echo [dB, as cell_echo_db] (-inf: none). The
    /// scale against which a pair's possible error is judged; empty: every flagged pair counts.
    std::vector<float> base_db;
    /// The error [dB, as base_db] below which a pair is not worth refining whatever its bin: each base cell's
    /// even share of the error the rel L1 tolerance allows the whole image (-inf: none).
    double cell_share_db = -INFINITY;

  private:
    /// Level steps [dB] between neighbours above which they count as not smooth, at a tolerance_db.
    struct Steps {
        double jump_db;       ///< in echo density: kJumpPerToleranceDb x the tolerance
        double range_jump_db; ///< in echo per metre of range, on one plane with footprints spanning bins
        static Steps at(double tolerance_db) {
            return {kJumpPerToleranceDb * tolerance_db, kRangeJumpPerToleranceDb * tolerance_db};
        }
    };
    bool discontinuous_direct(const Node& x, const Column& cx, const Node& y, const Column& cy,
                              const EdgeRay& edge) const;
    /// What steps between x and y: -1 an edge (a miss or a surface edge), else the level step [dB] that
    /// exceeds its threshold in `steps`; NaN: none.
    double direct_step_db(const Node& x, const Node& y, const EdgeRay& edge, const Steps& steps) const;
    bool via_discontinuous(const Node& x, const Column& cx, const Node& y, const Column& cy) const;
    /// Multipath: the fraction of the continuations' echo that x and y may differ by (0.5 where one meets
    /// nothing or a surface edge lies between them; from the level step where that exceeds its threshold
    /// in `steps`); 0 where they meet one smooth surface.
    double via_step(const Node& x, const Node& y, const Steps& steps) const;
    bool surface_edge(const Hit& x, const glm::dvec3& px, const Hit& y, const glm::dvec3& py,
                      const EdgeRay& edge) const;
    bool worth_refining(const Node& x, const Column& cx, const Node& y, const Column& cy,
                        double step_db) const;
    bool significant_via(const Node& n, const Column& c, double f) const;
    bool significant_at(double density_db, double r, double footprint_m, const Node& n, const Column& c,
                        double f, bool shared = true) const;
    bool absorbed_across(double footprint_m) const;
    /// 10 log10(da bin_m / 2) [dB] for a column of width da (may_be_significant), from a per-thread cache.
    double half_width_bin_db(double da) const;
    /// |face normal . ray direction| of a node that hit, from its hit point (0 when too small to tell).
    double face_cos(const Node& n) const;
    /// Whether neither edge of a cell reaching half_width [rad] either side of the node's ray in elevation
    /// can pass the face plane's horizon (false: test the edges).
    bool no_horizon_within(const Node& n, double half_width) const;
    glm::dvec3 normal_direction_sonar(const Node& n) const;

    const SceneDesc& s_;
    const detail::RayFrame& frame_;
    bool multipath_;
    ShadeConstants k_;
    Steps
        refine_; ///< refinement's, at the scene's tolerance_db (range_jump_db: absorption across a cell too)
    Steps smooth_;         ///< edge_between's: at the tolerance, at most at kSmoothToleranceDb
    double bin_m_, gap_m_; ///< range bin width; half of it, the range disagreement that makes an edge
    double tol_rel_db_;    ///< 10 log10 of the relative error per bin the tolerance allows, / kErrorsPerBin
    bool specular_ = true; ///< some material has a specular lobe (mu > 0)
};

} // namespace sonarsim::adaptive

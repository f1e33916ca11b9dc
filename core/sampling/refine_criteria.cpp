// Adaptive sampling: the refinement criteria (see refine_criteria.hpp and core/sampling/README.md).
#include "core/sampling/refine_criteria.hpp"

#include "core/base/recent_values.hpp"
#include "core/shading/shade.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace sonarsim::adaptive {

RefineCriteria::RefineCriteria(const SceneDesc& scene, const detail::RayFrame& frame, bool multipath)
    : s_(scene), frame_(frame), multipath_(multipath), k_(shade_constants(scene)),
      refine_(Steps::at(scene.sampling.tolerance_db)),
      smooth_(Steps::at(std::min(scene.sampling.tolerance_db, kSmoothToleranceDb))),
      bin_m_(frame.grid->bin_m), gap_m_(0.5 * bin_m_),
      tol_rel_db_(10 * std::log10((std::pow(10.0, scene.sampling.tolerance_db / 10) - 1) / kErrorsPerBin)) {
    specular_ = scene.water.surface_material.mu > 0 || (scene.seafloor && scene.seafloor->material.mu > 0);
    for (const auto& o : scene.objects) specular_ = specular_ || o.material.mu > 0;
}

bool RefineCriteria::discontinuous(const Node& x, const Column& cx, const Node& y, const Column& cy,
                                   const EdgeRay& edge) const {
    return discontinuous_direct(x, cx, y, cy, edge) || (multipath_ && via_discontinuous(x, cx, y, cy));
}

bool RefineCriteria::discontinuous_direct(const Node& x, const Column& cx, const Node& y, const Column& cy,
                                          const EdgeRay& edge) const {
    // Whatever steps between them, neither cell's error could be significant: no need to look.
    if (!may_be_significant(x, cx) && !may_be_significant(y, cy)) return false;
    const double step_db = direct_step_db(x, y, edge, refine_);
    return step_db == step_db && worth_refining(x, cx, y, cy, step_db);
}

bool RefineCriteria::edge_between(const Node& x, const Node& y, const EdgeRay& edge) const {
    const double step_db = direct_step_db(x, y, edge, smooth_);
    return step_db == step_db || (multipath_ && via_step(x, y, smooth_) > 0);
}

double RefineCriteria::direct_step_db(const Node& x, const Node& y, const EdgeRay& edge,
                                      const Steps& steps) const {
    constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
    if (bool(x.hit) != bool(y.hit)) return -1;
    if (!x.hit) return kNone;
    if (surface_edge(*x.hit, x.p_m, *y.hit, y.p_m, edge)) return -1;
    const double density_step_db = std::abs(x.density_db - y.density_db);
    if (density_step_db > steps.jump_db) return density_step_db;
    // Cells whose range footprint spans bins spread their echo evenly over it; where the echo per metre
    // of range changes between neighbours on one plane (grazing incidence: r(e) is far from linear over
    // the cell), that spreading needs finer cells. Between the facets of a smooth tessellated surface
    // the change is the facets' own (their normals step), and the density test above bounds it.
    if (x.hit->prim != y.hit->prim || !(std::max(x.footprint_m, y.footprint_m) > bin_m_)) return kNone;
    const double per_metre_step_db = std::abs(x.per_metre_db - y.per_metre_db);
    return per_metre_step_db > steps.range_jump_db ? per_metre_step_db : kNone;
}

/// Multipath: the continuations of neighbouring mirror cells x and y meet different surfaces, or one
/// meets nothing, or their levels step, where that matters against the image (as for direct cells).
bool RefineCriteria::via_discontinuous(const Node& x, const Column& cx, const Node& y,
                                       const Column& cy) const {
    const double f = via_step(x, y, refine_);
    return f > 0 && (significant_via(x, cx, f) || significant_via(y, cy, f));
}

double RefineCriteria::via_step(const Node& x, const Node& y, const Steps& steps) const {
    if (!x.via->reflected && !y.via->reflected) return 0;
    const bool hx = bool(x.via->hit), hy = bool(y.via->hit);
    if (hx != hy) return 0.5;
    if (!hx) return 0;
    const Hit &a = *x.via->hit, &b = *y.via->hit;
    const double reach = x.via->dr_de * x.de + y.via->dr_de * y.de + gap_m_; // what a smooth surface spans
    const bool edge = a.material != b.material || (a.prim != b.prim && std::abs(a.t - b.t) > reach);
    if (edge) return 0.5;
    double step_db = std::abs(x.via->density_db - y.via->density_db);
    if (step_db <= steps.jump_db) {
        // As for direct cells: a ghost's footprint spanning bins spreads its echo evenly over it, so where
        // its echo per metre of range steps between neighbours on one plane (grazing at the scatterer)
        // the ghost needs finer cells.
        const double fx = x.via->dr_de * x.de, fy = y.via->dr_de * y.de;
        if (a.prim != b.prim || !(std::max(fx, fy) > bin_m_)) return 0;
        auto per_metre_db = [&](const Node& n, double footprint_m) {
            return n.via->density_db + 10 * std::log10(n.angle.c * n.de / std::max(footprint_m, bin_m_));
        };
        step_db = std::abs(per_metre_db(x, fx) - per_metre_db(y, fy));
        if (step_db <= steps.range_jump_db) return 0;
    }
    return 0.5 * (1 - std::pow(10.0, -0.1 * step_db));
}

/// True when a surface edge lies between the hits of x and y: another material, or, on one object, hits
/// on different triangles whose planes disagree by more than half a range bin about where the ray along
/// the cells' shared edge meets the surface (a silhouette, an occlusion, a crease that moves echo between
/// bins). The planes are the faces the hits lie on (Hit::face_normal): this is a test of where the
/// surface is; how smoothly it echoes (shading normals) is judged by the density tests. A finely
/// tessellated smooth surface passes: its planes agree to second order in the spacing, so the number of
/// rays does not grow with the number of triangles.
bool RefineCriteria::surface_edge(const Hit& x, const glm::dvec3& px, const Hit& y, const glm::dvec3& py,
                                  const EdgeRay& edge) const {
    if (x.material != y.material) return true;
    if (x.material == kFloorMaterial || x.material == kSurfaceMaterial || x.prim == y.prim) return false;
    glm::dvec3 d_near;
    if (edge.dir_near(frame_, d_near)) {
        const double rx = detail::plane_range_near(frame_.origin, px, x.face_normal, d_near);
        const double ry = detail::plane_range_near(frame_.origin, py, y.face_normal, d_near);
        // Decided by the near direction unless |rx - ry| lies within its error of gap_m_.
        if (rx < 0 || ry < 0) return true;
        if (rx > 0 && ry > 0 && std::abs(std::abs(rx - ry) - gap_m_) > 1e-7 * (rx + ry)) {
            return std::abs(rx - ry) > gap_m_;
        }
    }
    const glm::dvec3 d_edge = edge.dir(frame_);
    const double rx = detail::plane_range(frame_.origin, px, x.face_normal, d_edge);
    const double ry = detail::plane_range(frame_.origin, py, y.face_normal, d_edge);
    return rx < 0 || ry < 0 || std::abs(rx - ry) > gap_m_;
}

/// A pair whose cells disagree is refined only where the error it can cause is significant against the
/// image: half the echo of a cell at a surface edge, half the difference of the two levels on one
/// surface. Pairs on rough surfaces whose cells are a small part of their bins' echo stay coarse;
/// silhouettes, shadows and bright facets against their background do not.
/// step_db: the difference of the two levels (a negative value: an edge).
bool RefineCriteria::worth_refining(const Node& x, const Column& cx, const Node& y, const Column& cy,
                                    double step_db) const {
    const double f = step_db < 0 ? 0.5 : 0.5 * (1 - std::pow(10.0, -0.1 * step_db));
    return significant(x, cx, f) || significant(y, cy, f);
}

/// Whether an error of a fraction `f` of the echo of node n's cell (in column c), spread over the cell's
/// range footprint, exceeds the relative error per bin that the tolerance allows in the base image's bin
/// of that range. Computed in dB, so that no level underflows.
bool RefineCriteria::significant(const Node& n, const Column& c, double f) const {
    if (base_db.empty()) return true;
    return n.hit && significant_at(n.density_db, n.hit->t, n.footprint_m, n, c, f);
}

bool RefineCriteria::may_be_significant(const Node& n, const Column& c) const {
    if (base_db.empty()) return true;
    if (!n.hit) return false;
    if (!(n.footprint_m < INFINITY)) return true; // an edge-on face (footprint inf or NaN): the full test
    const double b = std::floor(frame_.grid->bin_position(n.hit->t));
    if (!(b >= 0 && b < s_.sonar.range_bins)) return false;
    const double bin_db = base_db[size_t(c.beam) * size_t(s_.sonar.range_bins) + size_t(b)];
    // significant_at's level at f = 1/2, from the echo per metre set_width keeps: density + 10 log10(c de /
    // max(footprint, bin)) + 10 log10(da bin / 2); both logarithms within 1e-12 dB, hence the margin.
    const double bound_db = n.per_metre_db + half_width_bin_db(c.da) + kBoundMarginDb;
    return bound_db > tol_rel_db_ + bin_db && bound_db > cell_share_db;
}

double RefineCriteria::half_width_bin_db(double da) const {
    // Columns come in a few widths (a beam's width / 3^k).
    return recent_value<4>(std::pair(da, bin_m_), [](const std::pair<double, double>& k) {
        return kDbPerOctave * fast::log2_positive(0.5 * k.first * k.second);
    });
}

bool RefineCriteria::significant_via(const Node& n, const Column& c, double f) const {
    // Ghosts are weak against the image: the cell share (an image-wide bound) would leave them all coarse.
    return n.via->hit &&
           significant_at(n.via->density_db, n.via->hit->t, n.via->dr_de * n.de, n, c, f, /*shared=*/false);
}

/// The same for an echo of `density_db` per steradian at range r spread over `footprint_m`.
bool RefineCriteria::significant_at(double density_db, double r, double footprint_m, const Node& n,
                                    const Column& c, double f, bool shared) const {
    if (base_db.empty()) return true;
    if (!(f > 0)) return false;
    const double b = std::floor(frame_.grid->bin_position(r));
    if (!(b >= 0 && b < s_.sonar.range_bins)) return false; // outside the window: no bin to spoil
    const double bin_db = base_db[size_t(c.beam) * size_t(s_.sonar.range_bins) + size_t(b)]; // may be -inf
    const double error_db =
        density_db + 10 * std::log10(f * n.angle.c * n.de * c.da / std::max(1.0, footprint_m / bin_m_));
    return error_db > tol_rel_db_ + bin_db && (!shared || error_db > cell_share_db);
}

/// Direction of normal incidence on the node's surface (its shading normal), in the sonar frame.
glm::dvec3 RefineCriteria::normal_direction_sonar(const Node& n) const {
    const glm::dvec3 v = glm::dot(n.hit->normal, n.p_m - frame_.origin) > 0 ? n.hit->normal : -n.hit->normal;
    return glm::transpose(frame_.R) * v;
}

bool RefineCriteria::needs_split_alone(const Node& n, const Angle& a) const {
    if (!n.hit) return false;
    if (absorbed_across(n.footprint_m)) return true;
    const Material& m = material_of(s_, n.hit->material);
    if (specular_ && m.mu > 0 && n.de > deg2rad(m.h_deg) / 4) {
        const glm::dvec3 v = normal_direction_sonar(n);
        const double e_star = std::atan2(v.z, v.x * a.c + v.y * a.s);
        if (std::abs(e_star - n.angle.rad) < n.de / 2 + 2 * deg2rad(m.h_deg)) return true;
    }
    // A horizon inside: an edge ray that misses the face's plane. The edges' directions are cos(de/2) d
    // -+ sin(de/2) d_e (d_e the unit derivative in elevation), so n.d keeps its sign at both edges while the
    // ray is steeper to the plane than de/2 (no_horizon_within; its margin covers rounding, so that the tests
    // below would say the same).
    if (no_horizon_within(n, n.de / 2)) return false;
    // Otherwise edge directions by the angle-sum identities decide unless an edge ray nearly grazes the
    // plane; then sin and cos of the edge decide.
    const Angle& h = detail::half_angle(n.de);
    for (int sign : {-1, +1}) {
        const double edge = sign < 0 ? n.angle.rad - n.de / 2 : n.angle.rad + n.de / 2;
        const Angle near(edge, n.angle, h, sign);
        const double r =
            detail::plane_range_near(frame_.origin, n.p_m, n.hit->face_normal, frame_.dir(a, near));
        if (r == r ? r < 0
                   : detail::plane_range(frame_.origin, n.p_m, n.hit->face_normal,
                                         frame_.dir(a, Angle(edge))) < 0)
            return true;
    }
    return false;
}

double RefineCriteria::face_cos(const Node& n) const {
    const double num = std::abs(glm::dot(n.hit->face_normal, n.p_m - frame_.origin));
    return num > 1e-9 && num < 1e12 ? num / n.hit->t : 0.0;
}

bool RefineCriteria::no_horizon_within(const Node& n, double half_width) const {
    // With |n.d| = sin(phi) (phi the grazing angle), |n.d_e| <= cos(phi) as d_e is perpendicular to d, so at
    // either edge |n.d| >= sin(phi - w): its sign holds while phi > w, that is |n.d| > sin(w), and x >= sin
    // x. 3e-6 keeps |n.d| at the edges above plane_range_near's 1e-6, rounding included.
    return half_width < 1 && face_cos(n) > half_width + 3e-6;
}

/// Absorption alone changes the echo by more than the range-spreading threshold across a cell's range
/// footprint, which spreads its echo evenly (very high frequencies: at 10 MHz, 110 dB per metre of range;
/// where a bin holds few cells, at the aperture's edges, the split of a cell's echo between bins must then
/// follow the level within it).
bool RefineCriteria::absorbed_across(double footprint_m) const {
    return 2 * k_.alpha_db_per_m * footprint_m > refine_.range_jump_db;
}

bool RefineCriteria::absorbed_across_azimuth(const Node& n, const Column& c, const Angle& a) const {
    if (!n.hit || !(k_.alpha_db_per_m > 0)) return false;
    // |n.d_a| <= 1, so the footprint below is at most t da / |n.d| (|n.d| from the hit point, to a relative
    // 1e-8 where it exceeds 1e-6): below the threshold, no need for the directions.
    const double cos_face = face_cos(n);
    if (cos_face > 1e-6 && !absorbed_across(n.hit->t * c.da / cos_face * (1 + 1e-6))) return false;
    const glm::dvec3 d = frame_.dir(a, n.angle);
    const glm::dvec3 d_a = frame_.R * glm::dvec3(-n.angle.c * a.s, n.angle.c * a.c, 0);
    const glm::dvec3& nf = n.hit->face_normal; // the footprint's plane, as in make_cell
    return absorbed_across(std::abs(n.hit->t * glm::dot(nf, d_a) / glm::dot(nf, d)) * c.da);
}

bool RefineCriteria::specular_in_azimuth(const Node& n, double a_lo, double a_hi, double da) const {
    if (!specular_ || !n.hit) return false;
    const Material& m = material_of(s_, n.hit->material);
    if (!(m.mu > 0) || da <= deg2rad(m.h_deg) / 4) return false;
    const glm::dvec3 v = normal_direction_sonar(n);
    const double a_star = std::atan2(v.y, v.x), h = deg2rad(m.h_deg);
    return a_star > a_lo - 2 * h && a_star < a_hi + 2 * h;
}

} // namespace sonarsim::adaptive

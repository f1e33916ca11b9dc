// The hits a trace keeps for shading: per ray its cell (point, normal's incidence, solid angle, footprint,
// material), multipath ghosts, the tracer's error estimate; and how a trace is controlled from outside.
// Plain data: sampling/ fills it, shading/ reads it.
#pragma once
#include "core/data/channels.hpp"
#include "core/data/scene.hpp"

#include <atomic>
#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <stdexcept>
#include <vector>

namespace sonarsim {

/// Material index of the seafloor; object i has material index i + 1.
constexpr unsigned kFloorMaterial = 0;
/// Material index of the water surface (water.surface_height_m): -2 as a signed ground-truth id.
constexpr unsigned kSurfaceMaterial = 0xFFFFFFFEu;

/// One ray and the solid-angle cell [e +- de/2] x [a +- da/2] it stands for.
struct Cell {
    glm::vec3 point_m;    ///< first hit [m, world]
    float range_m;        ///< distance from the sonar to the hit [m]
    float cos_incidence;  ///< cos of the angle between the surface normal and the reversed ray
    float solid_angle_sr; ///< dOmega = cos e de da [sr], times the elevation pattern B_v(e) when there is one
    float range_e_lo_m,
        range_e_hi_m; ///< range on the hit plane at the cell's lower / upper elevation edge [m]
    float range_a_lo_m, range_a_hi_m;         ///< range on the hit plane at the cell's two azimuth edges [m]
    float azimuth_rad, azimuth_width_rad;     ///< the cell's centre and width in azimuth (sonar frame)
    float elevation_rad, elevation_width_rad; ///< the cell's centre and width in elevation (sonar frame)
    std::uint32_t material;                   ///< kFloorMaterial or object index + 1
    std::uint32_t elevation_index;
    /// d ln(echo per metre of range) / d range across the elevation footprint [1/m]: the cell's echo is
    /// spread over its footprint with this linear trend (footprint.hpp); 0: evenly.
    float spread_slope_per_m = 0;
    /// Jittered placement: which of the stratum's two independent rays this is (0 or 1); 0 otherwise.
    std::uint8_t half = 0;
};

/// An echo that reached a scatterer by way of specular reflections (multipath.cpp), on the beam it arrives
/// in. `cell` is the cell as seen from the image sonar (the sonar mirrored in each mirror of the chain):
/// range_m and its footprint are half the whole path length, azimuth and elevation the arrival direction,
/// point the scatterer, cos_incidence the incidence of the leg whose solid angle the cell stands for (the
/// `area leg`), solid_angle_sr that solid angle times sqrt(B_v(transmit) B_v(receive)).
/// Paths: double (area leg and other leg both by the mirrors: the image sonar's monostatic echo), or mixed
/// (one leg by the mirrors, one direct; the two directions are two ghosts of equal energy).
struct GhostCell {
    Cell cell;
    float other_leg_m; ///< length of the leg that is not the area leg [m] (double paths: range_m)
    float cos_other;   ///< cos of that leg's incidence at the scatterer (double paths: cos_incidence)
    std::uint8_t tx_bounces = 0, rx_bounces = 0; ///< reflections on the way out and back
    std::uint32_t beam = 0;                      ///< the beam it arrives in
    std::uint32_t mirror_material[2] = {0, 0};   ///< the chain's mirrors, sonar side first
    float mirror_cos[2] = {1, 1};                ///< cos of the incidence at each mirror
    glm::vec3 mirror_point_m[2] = {};            ///< where the path meets each mirror [m, world]
    int order() const { return tx_bounces + rx_bounces; }
    int mirrors() const { return tx_bounces > rx_bounces ? tx_bounces : rx_bounces; } ///< of the chain
    bool mixed() const { return tx_bounces != rx_bounces; }
};

struct AdaptiveEstimateCells; // sampling/adaptive_sampler.hpp

struct TraceResult {
    int beams = 0;
    std::vector<std::vector<Cell>> cells; ///< per beam: the cells whose ray hit something within reach
    /// Per beam: multipath echoes arriving in it (empty without mirrors or with sampling.bounces 0).
    std::vector<std::vector<GhostCell>> ghosts;
    std::uint64_t rays_traced = 0;
    std::uint64_t multipath_rays = 0; ///< continuation and shadow rays of the multipath ghosts
    /// Jittered placement: the cells (and ghosts) form two independent estimates of the image (Cell::half),
    /// from which shading estimates the sampling error (estimate_error).
    bool halves = false;
    /// Jittered placement, on every few traced beams (the estimate's samples) (the others empty): the same
    /// rays' cells with each ray's whole stratum as its cell, from which shading estimates the footprint's
    /// bias.
    std::vector<std::vector<Cell>> stratum_cells;
    /// Adaptive scheme: estimated error of this sampling (difference to one refinement level coarser).
    struct ErrorEstimate {
        bool valid = false;
        double rel_l1 = 0, median_abs_db = 0, p95_abs_db = 0;
        int passes = 0;
        bool budget_reached = false; ///< refinement stopped at sampling.max_rays before the tolerance was met
        /// sampling.estimate strict was applied: the sampler added ray columns where its azimuth probe found
        /// the larger share of the error (fast only reports it)
        bool strict = false;
        /// Fast: the part of rel_l1 that its azimuth probe saw and the sampler did not refine (one ray column
        /// per beam across the beam's width; strict refines it); included in rel_l1 and the quantiles.
        double azimuth_rel_l1 = 0;
        /// Jittered: rel_l1's two terms summed apart: the halves' difference and the footprint's bias.
        double variance_rel_l1 = 0, footprint_rel_l1 = 0;
        /// Whether both of the sampler's targets are met: median |dB| <= tolerance_db and rel L1 <=
        /// tolerance_rel_l1.
        bool meets(const SamplingParams& p) const {
            return median_abs_db <= p.tolerance_db && rel_l1 <= p.tolerance_rel_l1;
        }
    } error_estimate;
    /// Adaptive scheme, full quality, traced with TraceControl::keep_placement: what its error estimate was
    /// made from besides these cells (each group's sample beam one level coarser, and its azimuth probe),
    /// kept so that the estimate can be made again for a new shading of the same placement
    /// (reestimate_error); null otherwise (half the hits' bytes, twice with multipath).
    std::shared_ptr<const AdaptiveEstimateCells> estimate_cells;
    bool preview = false; ///< a coarse pass only (TraceControl::preview): no refinement, no error estimate
    double trace_ms = 0;
};

/// Control of one trace from outside: cancellation by another thread, and a coarse preview.
struct TraceControl {
    /// When another thread sets it, the trace stops within a few milliseconds and throws TraceCancelled.
    const std::atomic<bool>* cancel = nullptr;
    /// Adaptive scheme: the base grid only (no refinement, no error estimate), for an image within a
    /// frame budget while the user drags; uniform and spread ignore it.
    bool preview = false;
    /// With preview, the adaptive scheme: a Simulator traces a jittered grid instead of the base grid, one
    /// whose estimated median |dB| error over the echoing bins is about this [dB] (the screen's precision:
    /// half a grey level of the display range, half_grey_level_db), sized from its last such preview's
    /// estimate, so the preview carries its own error estimate; 0: the base grid.
    double preview_median_db = 0;
    /// The time such a preview's trace and shading may take [ms] (a frame of 33 ms also forms the fan and
    /// draws): its grid grows no larger than that allows, and its estimate then says what it reaches; 0: no
    /// limit.
    double preview_budget_ms = 15;
    /// The beams to trace (one flag per beam), or null for all: the others are left without cells (motion
    /// during a frame traces each ping's beams from its own pose).
    const std::vector<char>* beams = nullptr;
    /// Adaptive scheme: every pass pays the ray budget in a fixed order. By default only a pass likely to
    /// reach the budget, or refused a ray first come, does; the image is the same bytes either way.
    bool ordered_budget = false;
    /// Adaptive scheme, full quality, after a change of values that steer the sampler only (Stage::Place):
    /// keep the hits and re-shade them while their error estimate, made anew with the new shading
    /// (reestimate_error), still serves (kept_placement_serves), and re-trace only where it does not. The
    /// image then depends on the scene shaded before (a fresh Simulator places its rays anew).
    /// The viewer keeps; render, batch, study and Python re-trace, so their bytes depend on the scene alone.
    /// A trace with it keeps what its estimate is made from (TraceResult::estimate_cells).
    bool keep_placement = false;
    bool cancelled() const { return cancel && cancel->load(std::memory_order_relaxed); }
    bool traces(int beam) const { return !beams || (*beams)[size_t(beam)]; }
    /// How many of n beams are traced.
    int traced_beams(int n) const {
        int k = 0;
        for (int i = 0; i < n; ++i) k += traces(i);
        return k;
    }
};

/// Thrown by trace() when TraceControl::cancel was set.
struct TraceCancelled : std::runtime_error {
    TraceCancelled() : std::runtime_error("trace cancelled") {}
};

} // namespace sonarsim

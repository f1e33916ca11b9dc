// Adaptive sampling, internal: what one image's trace shares across its passes (the scene, the frame, the
// criteria, the ray budget) and the steps of a pass, each in its own file:
// refine_elevation.cpp (trace and refine a column), refine_azimuth.cpp (split columns where neighbours
// disagree), adaptive_pass.cpp (one pass: base grid, refinement, cells, error estimate), adaptive.cpp (the
// passes).
#pragma once
#include "core/sampling/adaptive_node.hpp"
#include "core/sampling/refine_criteria.hpp"

#include <tbb/enumerable_thread_specific.h>

#include <atomic>
#include <deque>
#include <cstdint>

namespace sonarsim::adaptive {

struct Sampler {
    const SceneGeometry& g;
    const SceneDesc& s;
    const TraceControl& control;
    detail::RayFrame frame;
    bool multipath; ///< ghosts to find (sampling.bounces and a mirror)
    detail::Multipath mp;
    RefineCriteria criteria;
    double phi; ///< the traced elevation aperture [rad]
    int elevation_levels, azimuth_levels;
    /// Azimuth levels split where neighbouring columns disagree: kEdgeAzimuthLevels in the first pass, one
    /// in a denser pass (its columns cost the denser grid's rays; a specular lobe still splits to the end).
    int edge_azimuth_levels = kEdgeAzimuthLevels;
    mutable std::atomic<std::uint64_t> rays{0}; ///< rays traced or reserved in this image, all passes
    mutable std::atomic<bool> budget_hit{false};
    std::vector<Angle> base_angles; ///< the base grid's elevations (set_base_grid)
    std::vector<int> traced;        ///< the beams traced (TraceControl::beams; all by default)
    /// Multipath: the nodes' continuations (Node::via), per thread, in blocks that never move.
    mutable tbb::enumerable_thread_specific<std::deque<Via>> via_store;

    /// Elevations of a pass's base grid of M0 rays (once per pass instead of once per column).
    void set_base_grid(int M0);

    Sampler(const SceneGeometry& geo, const SceneDesc& scene, const TraceControl& c);

    /// Every stride-th traced beam: the sample the error estimates look at.
    std::vector<int> sampled_beams(int stride) const {
        std::vector<int> out;
        for (size_t k = 0; k < traced.size(); k += size_t(stride)) out.push_back(traced[k]);
        return out;
    }
    /// Rays of a base grid of M0 elevation rays over the traced beams.
    double base_rays(int M0) const { return double(M0) * double(traced.size()) * s.sampling.azimuth_rays; }

    /// Takes n rays from the image's budget (sampling.max_rays); false (and nothing taken) when it is spent.
    bool reserve(std::uint64_t n) const;

    // refine_elevation.cpp
    /// One ray (a, e) standing for a cell of width de in elevation, with what the criteria read.
    Node trace_node(const Angle& a, const Angle& e, double de, int group) const;
    /// The base grid of one column: base cells [j0, j1) of M0.
    Column trace_column(double a_rad, double da, int M0, int beam, int j0, int j1) const;
    /// Ternary refinement of a column's cells down to kElevationLevels.
    void refine_column(Column& col, int M0) const;

    // refine_azimuth.cpp
    /// Splits columns in azimuth (kAzimuthLevels levels) where neighbours disagree or a cell needs it.
    void refine_azimuth(Beams& beams, int M0) const;

    // adaptive_pass.cpp
    /// Cells of a column, and their multipath ghosts (with multipath); `coarse` merges every complete
    /// sibling triple into its middle cell (one level up). Returns the ghosts' rays.
    std::uint64_t cells_of(const Column& c, bool coarse, double da, std::vector<Cell>& out,
                           std::vector<GhostCell>& ghosts) const;

  private:
    void trace_continuation(Node& n, const Angle& a) const;
    /// Marks the nodes of `col` to split at this level; returns how many.
    size_t mark_for_split(Column& col, const Angle& a, double de_min) const;
    /// Replaces each marked node by three of a third its width (the middle one is the node itself).
    void split_marked(Column& col, const Angle& a, size_t marked, int& next_group) const;
};

/// One pass at base grid M0 elevation rays: traces, refines, shades and (unless previewing) estimates the
/// error against the image one level coarser. With `may_skip` (a denser pass can follow), a base grid whose
/// own estimated error is kSkipFactor x a tolerance or more is not refined: `skipped`, `est` is the base
/// grid's, and the result holds no cells.
TraceResult trace_pass(Sampler& sampler, int M0, TraceResult::ErrorEstimate& est, bool may_skip,
                       bool& skipped);

} // namespace sonarsim::adaptive

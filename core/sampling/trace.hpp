// Tracing: cast each beam's rays into the scene and keep, per ray, what shading needs (the "hits").
// Physics is not applied here, so a change of L_S, L_N, alpha or a material re-shades without re-tracing.
#pragma once
#include "core/data/hits.hpp"
#include "core/data/polar_image.hpp"
#include "core/geometry/geometry.hpp"
#include "core/shading/accumulate.hpp"

namespace sonarsim {

/// Traces the scene with the ray placement it asks for (sampling.placement). A placement that shades its
/// hits to place them (adaptive) runs the whole image's pass through `pass`, when given: its take() is then
/// the pass of the hits returned, if it ran one.
TraceResult trace(const SceneGeometry& geometry, const SceneDesc& scene, const TraceControl& control = {},
                  ImagePass* pass = nullptr);

/// The paper's regular grid: beams x azimuth_rays x elevation_rays rays at cell centres (midpoint rule).
TraceResult trace_uniform(const SceneGeometry& geometry, const SceneDesc& scene,
                          const TraceControl& control = {});

/// Adaptive: starts from the regular grid and splits cells (ternary, in elevation; in azimuth over the base
/// cells where neighbouring columns disagree) where the error they could leave is significant against the
/// base grid's echo in their bins and sampling.tolerance_db: surface edges, steps in echo level, specular
/// lobes, horizons, grazing footprints. All rays come out of sampling.max_rays. Fills `error_estimate`.
TraceResult trace_adaptive(const SceneGeometry& geometry, const SceneDesc& scene,
                           const TraceControl& control = {}, ImagePass* pass = nullptr);

/// The error estimate of an adaptive trace's placement (`hits`, with TraceResult::estimate_cells) made anew
/// with `scene`'s shading, a scene that differs from the traced one in values that steer the sampler only
/// (Stage::Place): the same estimator on the same cells. `image`: hits shaded with `scene`, whose sample
/// beams' columns are the estimate's fine image; null: those beams are shaded here. The same scene gives the
/// trace's own estimate.
TraceResult::ErrorEstimate reestimate_error(const TraceResult& hits, const SceneDesc& scene,
                                            const PolarImage* image = nullptr);

/// Whether a kept placement serves a new shading, from its estimate made anew (`anew`) and its trace's own
/// (`traced`): `anew` meets the tolerances, or, where the trace itself stopped short of them (at the ray
/// budget or the last refinement level, which a re-trace would reach again), it is within one tolerance of
/// what the trace reached, in rel L1 and in median |dB|.
bool kept_placement_serves(const TraceResult::ErrorEstimate& anew, const TraceResult::ErrorEstimate& traced,
                           const SamplingParams& sampling);

/// Approximate bytes a trace's hits hold (cells, ghosts, strata, the adaptive estimate's cells).
std::size_t hits_bytes(const TraceResult& hits);

/// Jittered: per beam azimuth_rays x elevation_rays strata of two rays each, placed independently inside
/// their stratum by a seeded hash (the same scene traces the same rays); the two sets (Cell::half) are two
/// independent estimates of the image, from which shading estimates the error (jittered.cpp).
TraceResult trace_jittered(const SceneGeometry& geometry, const SceneDesc& scene,
                           const TraceControl& control = {});

} // namespace sonarsim

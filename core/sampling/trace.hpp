// Tracing: cast each beam's rays into the scene and keep, per ray, what shading needs (the "hits").
// Physics is not applied here, so a change of L_S, L_N, alpha or a material re-shades without re-tracing.
#pragma once
#include "core/data/hits.hpp"
#include "core/geometry/geometry.hpp"

namespace sonarsim {

/// Traces the scene with the ray placement it asks for (sampling.placement).
TraceResult trace(const SceneGeometry& geometry, const SceneDesc& scene, const TraceControl& control = {});

/// The paper's regular grid: beams x azimuth_rays x elevation_rays rays at cell centres (midpoint rule).
TraceResult trace_uniform(const SceneGeometry& geometry, const SceneDesc& scene,
                          const TraceControl& control = {});

/// Adaptive: starts from the regular grid and splits cells (ternary, in elevation; in azimuth over the base
/// cells where neighbouring columns disagree) where the error they could leave is significant against the
/// base grid's echo in their bins and sampling.tolerance_db: surface edges, steps in echo level, specular
/// lobes, horizons, grazing footprints. All rays come out of sampling.max_rays. Fills `error_estimate`.
TraceResult trace_adaptive(const SceneGeometry& geometry, const SceneDesc& scene,
                           const TraceControl& control = {});

/// Jittered: per beam azimuth_rays x elevation_rays strata of two rays each, placed independently inside
/// their stratum by a seeded hash (the same scene traces the same rays); the two sets (Cell::half) are two
/// independent estimates of the image, from which shading estimates the error (jittered.cpp).
TraceResult trace_jittered(const SceneGeometry& geometry, const SceneDesc& scene,
                           const TraceControl& control = {});

} // namespace sonarsim

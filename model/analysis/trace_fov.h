#pragma once
// The FOV of one trace as the product shows it: the studio's live trace (Gaze and Retina
// docks), the design report and `fovea-cli trace` all take `fov_deg` from here, so the studio
// and the CLI agree for the same scene, gaze and shifts.
//  - exact (FovMethod::Edges, the default): the continuous FOV with its edges root-found by
//    single rays (fov_edges.h) — the estimator of `sweep`, `compare-shift` and the fit, so a
//    trace at a sweep's gaze and x_p gives the sweep's FOV;
//  - dense: the same continuous FOV counted on the traced ray grid (trace_evaluator.h
//    continuousFov; its error is about a ray spacing, 1-2 deg at 4 000 rays/λ);
//  - extent: the tracer's lit extent, max - min of the lit field angles (TraceResult::fov_deg,
//    holes included; what `trace` reported as fov_deg before the exact estimator).
// All with the arrival-direction definition ("ours", trace_evaluator.h FovAngle::Arrival).

#include <vector>

#include "model/analysis/trace_evaluator.h"
#include "model/physics/trace.h"
#include "model/scene/scene.h"

namespace fovea {

struct TraceFov {
  FovDeg exact, dense, extent;
  FovDeg shown(FovMethod m) const { return m == FovMethod::Dense ? dense : exact; }
};

// The exact FOV for the trace options' gaze (default: the scene's), HOE shift, source shift,
// wavelength, threshold and polarisation. Costs ~1 ms (single rays), independent of o.rays.
FovDeg exactTraceFov(const Scene& scene, const TraceOptions& o);
// The dense continuous FOV of a trace's rays (ray_list or field_rays, whichever is filled).
FovDeg denseTraceFov(const TraceResult& r, double efficiency_threshold);
// The three of a finished trace.
TraceFov traceFov(const Scene& scene, const TraceResult& r, const TraceOptions& o);

}  // namespace fovea

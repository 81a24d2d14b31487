#include "model/analysis/trace_evaluator.h"

#include <cmath>
#include <stdexcept>

// The tracer is written in parallel on another branch; until it is merged this file
// builds without it and the gaze studies report that the tracer is missing.
#if __has_include("model/physics/trace.h")
#include <memory>

#include "model/physics/trace.h"
#include "model/physics/trace_pipeline.h"
#define FOVEA_HAVE_TRACE 1
#else
#define FOVEA_HAVE_TRACE 0
#endif

namespace fovea {

bool traceEvaluatorAvailable() {
  return FOVEA_HAVE_TRACE != 0;
}

FovEvaluator traceEvaluator(const TraceEvaluatorOptions& options) {
#if FOVEA_HAVE_TRACE
  // One memoising pipeline per concurrent caller (the gaze studies evaluate in parallel);
  // only the FOV, the pupil efficiencies and their uniformity are used, so rays that cannot
  // reach the pupil skip the coupled-wave step.
  auto pool = std::make_shared<TracePipelinePool>();
  return [options, pool](const Scene& scene, const FovQuery& q) {
    TraceOptions t;
    t.gaze_deg = q.gaze_deg;
    t.hoe_shift_mm = q.hoe_shift_mm;
    t.source_shift_mm = q.source_shift_mm;
    t.wavelength_nm = options.wavelength_nm;
    t.rays = options.rays;
    t.efficiency_threshold = options.efficiency_threshold;
    t.cull_to_pupil = true;
    auto pipeline = pool->acquire();
    const TraceResult r = pipeline->run(scene, t);
    FovSample f;
    f.horizontal_deg = r.fov_deg.horizontal;
    f.vertical_deg = r.fov_deg.vertical;
    f.diagonal_deg = r.fov_deg.diagonal;
    f.mean_efficiency = r.mean_efficiency;
    f.rays_in_pupil = r.rays_in_pupil;
    f.efficiency_uniformity = r.efficiency_uniformity;  // 1 - std/mean over the rays reaching the pupil
    return f;
  };
#else
  (void)options;
  throw std::runtime_error("the HOE ray tracer (model/physics/trace.h) is not part of this build yet");
#endif
}

}  // namespace fovea

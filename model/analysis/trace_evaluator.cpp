#include "model/analysis/trace_evaluator.h"

#include <cmath>
#include <stdexcept>

// The tracer is on main now: include it unconditionally. (A __has_include guard here let
// ccache's direct mode return an object compiled before trace.h existed: the manifest only
// lists headers that were read, so a build reported "tracer not part of this build".)
#include "model/physics/trace.h"
#define FOVEA_HAVE_TRACE 1

namespace fovea {

bool traceEvaluatorAvailable() {
  return FOVEA_HAVE_TRACE != 0;
}

FovEvaluator traceEvaluator(const TraceEvaluatorOptions& options) {
#if FOVEA_HAVE_TRACE
  return [options](const Scene& scene, const FovQuery& q) {
    TraceOptions t;
    t.gaze_deg = q.gaze_deg;
    t.hoe_shift_mm = q.hoe_shift_mm;
    t.source_shift_mm = q.source_shift_mm;
    t.wavelength_nm = options.wavelength_nm;
    t.rays = options.rays;
    t.efficiency_threshold = options.efficiency_threshold;
    t.keep_rays = true;
    const TraceResult r = traceScene(scene, t);
    FovSample f;
    f.horizontal_deg = r.fov_deg.horizontal;
    f.vertical_deg = r.fov_deg.vertical;
    f.diagonal_deg = r.fov_deg.diagonal;
    f.mean_efficiency = r.mean_efficiency;
    f.rays_in_pupil = r.rays_in_pupil;
    // Uniformity over the rays that reach the pupil: 1 - standard deviation / mean.
    double sum = 0, sum2 = 0;
    int n = 0;
    for (const TracedRay& ray : r.ray_list) {
      if (!ray.in_pupil) continue;
      sum += ray.efficiency;
      sum2 += ray.efficiency * ray.efficiency;
      ++n;
    }
    if (n > 0 && sum > 0) {
      const double mean = sum / n;
      const double var = std::max(0.0, sum2 / n - mean * mean);
      f.efficiency_uniformity = std::max(0.0, 1.0 - std::sqrt(var) / mean);
    }
    return f;
  };
#else
  (void)options;
  throw std::runtime_error("the HOE ray tracer (model/physics/trace.h) is not part of this build yet");
#endif
}

}  // namespace fovea

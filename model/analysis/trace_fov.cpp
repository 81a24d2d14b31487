#include "model/analysis/trace_fov.h"

#include "model/analysis/fov_edges.h"
#include "model/physics/ray_probe.h"

namespace fovea {

namespace {
FovDeg fovDegOf(const ContinuousFov& c) {
  return {c.horizontal_deg, c.vertical_deg, c.diagonal_deg};
}
}  // namespace

FovDeg exactTraceFov(const Scene& scene, const TraceOptions& o) {
  // The same call as traceEvaluator()'s Edges evaluator (trace_evaluator.cpp), so a trace and
  // a sweep sample at the same gaze and shift give the same number.
  RayProbeSetup setup;
  setup.gaze_deg = o.gaze_deg ? *o.gaze_deg : scene.eye.gaze_deg;
  setup.hoe_shift_mm = o.hoe_shift_mm;
  setup.source_shift_mm = o.source_shift_mm;
  setup.polarization = o.polarization;
  const RayProbe probe(scene, setup);
  EdgeFovOptions e;
  e.efficiency_threshold = o.efficiency_threshold;
  const std::vector<double> wavelengths =
      o.wavelength_nm ? std::vector<double>{*o.wavelength_nm} : scene.projector.wavelengths_nm;
  return fovDegOf(edgeFov(probe, wavelengths, e).fov);
}

FovDeg denseTraceFov(const TraceResult& r, double efficiency_threshold) {
  if (!r.field_rays.empty()) return fovDegOf(continuousFov(r.field_rays, efficiency_threshold));
  return fovDegOf(continuousFov(r.ray_list, efficiency_threshold));
}

TraceFov traceFov(const Scene& scene, const TraceResult& r, const TraceOptions& o) {
  TraceFov f;
  f.exact = exactTraceFov(scene, o);
  f.dense = denseTraceFov(r, o.efficiency_threshold);
  f.extent = r.fov_deg;
  return f;
}

}  // namespace fovea

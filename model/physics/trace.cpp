#include "model/physics/trace.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "model/physics/eye_model.h"
#include "model/physics/trace_internal.h"
#include "model/physics/trace_pipeline.h"
#include "model/scene/scene_geometry.h"

namespace fovea {

using detail::FovAccumulator;
using detail::tracedWavelengths;

// The gaze-independent half as a list of rays (no pupil information): the pipeline's rays.
std::vector<TracedRay> diffractScene(const Scene& scene, const TraceOptions& options) {
  TraceOptions o = options;
  o.keep_rays = true;
  o.cull_to_pupil = false;
  std::vector<TracedRay> rays = TracePipeline().run(scene, o).ray_list;
  for (TracedRay& r : rays) {
    r.in_pupil = false;
    r.field_deg = {0.0, 0.0};
    r.pupil_radius_mm = 0.0;
  }
  return rays;
}

TraceResult evaluateGaze(const Scene& scene, std::vector<TracedRay> rays, const TraceOptions& o) {
  TraceResult res;
  res.gaze_deg = o.gaze_deg ? *o.gaze_deg : scene.eye.gaze_deg;
  const EyePlacement eye = placeEye(scene, res.gaze_deg[0], res.gaze_deg[1]);
  const Eigen::Matrix3d eye_axes = rotationFromDeg({res.gaze_deg[0], res.gaze_deg[1], 0.0});
  const std::vector<double> wavelengths = tracedWavelengths(scene, o);

  FovAccumulator all;
  std::vector<FovAccumulator> per(wavelengths.size());
  res.per_wavelength.resize(wavelengths.size());
  std::vector<double> sum_pupil(wavelengths.size(), 0.0);
  double sum_pupil_all = 0.0, sum_hoe = 0.0;
  const std::size_t per_lambda = wavelengths.empty() ? 0 : rays.size() / wavelengths.size();

  for (std::size_t i = 0; i < rays.size(); ++i) {
    TracedRay& r = rays[i];
    // diffractScene() writes one block per wavelength; match by value for any other list.
    std::size_t w = per_lambda ? std::min(i / per_lambda, wavelengths.size() - 1) : 0;
    if (!wavelengths.empty() && wavelengths[w] != r.wavelength_nm)
      for (std::size_t k = 0; k < wavelengths.size(); ++k)
        if (wavelengths[k] == r.wavelength_nm) w = k;
    if (wavelengths.empty() || wavelengths[w] != r.wavelength_nm) continue;  // not a traced wavelength
    WavelengthTrace& wt = res.per_wavelength[w];
    ++res.rays;
    ++wt.rays;
    if (!r.hits_hoe) continue;
    ++res.rays_on_hoe;
    sum_hoe += r.efficiency;
    if (!r.exits) continue;
    r.field_deg = fieldAngleDeg(eye_axes, r.out_direction);
    const PupilCrossing c = crossPupil(eye, r.hoe_point, r.out_direction);
    r.pupil_radius_mm = c.radius_mm;
    r.in_pupil = c.in_pupil;
    if (!r.in_pupil) continue;
    ++res.rays_in_pupil;
    ++wt.rays_in_pupil;
    sum_pupil_all += r.efficiency;
    sum_pupil[w] += r.efficiency;
    if (r.efficiency >= o.efficiency_threshold) {
      ++res.rays_efficient;
      ++wt.rays_efficient;
      all.add(r.field_deg, -r.out_direction);
      per[w].add(r.field_deg, -r.out_direction);
    }
  }
  res.fov_deg = all.result();
  res.mean_efficiency = res.rays_in_pupil ? sum_pupil_all / res.rays_in_pupil : 0.0;
  res.mean_efficiency_on_hoe = res.rays_on_hoe ? sum_hoe / res.rays_on_hoe : 0.0;
  double sum2 = 0.0;
  for (const TracedRay& r : rays)
    if (r.in_pupil) sum2 += r.efficiency * r.efficiency;
  if (res.rays_in_pupil > 0 && sum_pupil_all > 0) {
    const double mean = sum_pupil_all / res.rays_in_pupil;
    res.efficiency_uniformity =
        std::max(0.0, 1.0 - std::sqrt(std::max(0.0, sum2 / res.rays_in_pupil - mean * mean)) / mean);
  }
  for (std::size_t w = 0; w < wavelengths.size(); ++w) {
    auto& wt = res.per_wavelength[w];
    wt.wavelength_nm = wavelengths[w];
    wt.fov_deg = per[w].result();
    wt.mean_efficiency = wt.rays_in_pupil ? sum_pupil[w] / wt.rays_in_pupil : 0.0;
  }
  if (o.keep_rays) res.ray_list = std::move(rays);
  return res;
}

TraceResult traceScene(const Scene& scene, const TraceOptions& options) {
  return TracePipeline().run(scene, options);
}

}  // namespace fovea

#include "model/physics/trace.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "model/physics/eye_model.h"
#include "model/physics/hoe_recording.h"
#include "model/physics/projector_rays.h"
#include "model/scene/scene_geometry.h"

namespace fovea {

namespace {

struct FovAccumulator {
  double yaw_min = std::numeric_limits<double>::infinity(), yaw_max = -yaw_min;
  double pitch_min = yaw_min, pitch_max = -yaw_min;
  double sum_max = -yaw_min, sum_min = yaw_min, diff_max = -yaw_min, diff_min = yaw_min;
  Eigen::Vector3d d_sum_max, d_sum_min, d_diff_max, d_diff_min;
  int count = 0;

  void add(const std::array<double, 2>& f, const Eigen::Vector3d& arrival_from) {
    ++count;
    yaw_min = std::min(yaw_min, f[0]);
    yaw_max = std::max(yaw_max, f[0]);
    pitch_min = std::min(pitch_min, f[1]);
    pitch_max = std::max(pitch_max, f[1]);
    const double s = f[0] + f[1], d = f[0] - f[1];
    if (s > sum_max) sum_max = s, d_sum_max = arrival_from;
    if (s < sum_min) sum_min = s, d_sum_min = arrival_from;
    if (d > diff_max) diff_max = d, d_diff_max = arrival_from;
    if (d < diff_min) diff_min = d, d_diff_min = arrival_from;
  }
  static double angleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / std::numbers::pi;
  }
  FovDeg result() const {
    if (count == 0) return {};
    return {yaw_max - yaw_min, pitch_max - pitch_min,
            std::max(angleDeg(d_sum_max, d_sum_min), angleDeg(d_diff_max, d_diff_min))};
  }
};

std::vector<double> tracedWavelengths(const Scene& scene, const TraceOptions& o) {
  if (o.wavelength_nm) return {*o.wavelength_nm};
  return scene.projector.wavelengths_nm;
}

}  // namespace

std::vector<TracedRay> diffractScene(const Scene& scene, const TraceOptions& o) {
  const Frame nominal = frameOf(scene.hoe.pose);
  Frame plate = nominal;
  plate.origin += o.hoe_shift_mm[0] * nominal.x() + o.hoe_shift_mm[1] * nominal.y();

  std::vector<LayerModel> layers;
  for (const auto& l : scene.hoe_layers) layers.push_back(makeLayerModel(scene.hoe, l));
  // Depth order along local +z (a probe from the world side walks it backwards).
  std::vector<int> order(layers.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return layers[a].offset_um < layers[b].offset_um; });

  const Eigen::Vector3d source = projectorSource(scene.projector, o.source_shift_mm);
  const std::vector<ProjectorRay> grid = projectorRays(scene.projector, o.rays);
  const std::vector<double> wavelengths = tracedWavelengths(scene, o);
  const double half_w = 0.5 * scene.hoe.size_mm[0], half_h = 0.5 * scene.hoe.size_mm[1];
  const double n_cover = scene.hoe.cover_index, n_sub = scene.hoe.substrate_index;

  std::vector<TracedRay> rays(grid.size() * wavelengths.size());
  const Eigen::Vector3d source_local = plate.toLocal(source);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), 256), [&](const auto& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      const ProjectorRay& pr = grid[i % grid.size()];
      TracedRay& r = rays[i];
      r.source = source;
      r.projector_direction = pr.direction;
      r.pixel = pr.pixel;
      r.wavelength_nm = wavelengths[i / grid.size()];
      const Eigen::Vector3d d = plate.axes.transpose() * pr.direction;
      if (d.z() == 0.0) continue;
      const double t = -source_local.z() / d.z();
      if (!(t > 0.0)) continue;
      const Eigen::Vector3d p = source_local + t * d;
      r.hoe_point = plate.toBench(p);
      if (std::abs(p.x()) > half_w || std::abs(p.y()) > half_h) continue;
      r.hits_hoe = true;

      const double n_in = source_local.z() < 0.0 ? n_cover : n_sub;
      double power = 1.0, best = -1.0;
      bool any_evanescent = false;
      for (std::size_t k = 0; k < order.size(); ++k) {
        const int li = d.z() > 0.0 ? order[k] : order[order.size() - 1 - k];
        const LayerModel& m = layers[li];
        const RecordedGrating g = recordAt(m, p.x(), p.y());
        if (!g.valid) continue;
        const LayerDiffraction ld =
            diffractLayer(m, g.k_recorded, d, n_in, n_cover, n_sub, r.wavelength_nm, o.polarization);
        if (!ld.entered) break;  // cannot enter the stack at all
        const double contribution = power * ld.grating.kogelnik.efficiency;
        any_evanescent = any_evanescent || ld.grating.evanescent;
        if (ld.exits) r.efficiency += contribution;
        if (contribution > best && (ld.exits || ld.tir)) {
          best = contribution;
          r.layer = li;
          r.tir = ld.tir;
          r.exits = ld.exits;
          r.xi = ld.grating.kogelnik.xi;
          r.nu = ld.grating.kogelnik.nu;
          if (ld.exits) {
            r.out_direction = plate.axes * ld.out_dir;
            r.towards_eye = (ld.out_dir.z() < 0.0) == (source_local.z() < 0.0);
          }
        }
        power *= ld.grating.kogelnik.zero_order;
      }
      r.evanescent = r.layer < 0 && any_evanescent;
      if (r.tir) r.exits = false;
    }
  });
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
  return evaluateGaze(scene, diffractScene(scene, options), options);
}

}  // namespace fovea

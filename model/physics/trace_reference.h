#pragma once
// A plain, unmemoised trace evaluated entirely in the floating type T: the same model as the
// pipeline (trace.h, trace_pipeline.h) written as one loop per ray. It is
//  - the long-double reference of the stability suite (tests/model/tst_numerical_stability),
//  - the float/double/long-double precision benchmark (`fovea-cli bench`),
//  - with T = double, the pipeline's check (tested): bit-identical but for the efficiencies,
//    which the pipeline takes from the SIMD Kogelnik batch (kogelnik_batch.h) and this loop
//    from the scalar closed forms (within 1e-12), so the memoised stages are checked against
//    the straightforward loop.
// Scene inputs are doubles; everything computed from them (plate hits, recording, Kogelnik,
// exit refraction, pupil crossing, field angles, FOV) is in T.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "model/physics/hoe_recording.h"
#include "model/physics/projector_rays.h"
#include "model/physics/trace.h"
#include "model/physics/trace_internal.h"
#include "model/scene/scene_geometry.h"

namespace fovea {

template <class T>
struct ReferenceRay {
  bool hits_hoe = false, exits = false, in_pupil = false;
  T efficiency = 0;
  int layer = -1;
  Vec3T<T> out_direction = Vec3T<T>::Zero();
  std::array<T, 2> field_deg{0, 0};
};

template <class T>
struct ReferenceTrace {
  std::vector<ReferenceRay<T>> rays;  // wavelength-major, like TraceResult::ray_list
  std::array<T, 3> fov_deg{0, 0, 0};  // horizontal, vertical, diagonal
  int rays_in_pupil = 0, rays_efficient = 0;
  T mean_efficiency = 0;
};

template <class T>
ReferenceTrace<T> referenceTrace(const Scene& scene, const TraceOptions& o) {
  using V = Vec3T<T>;
  using std::abs;
  const T pi = std::numbers::pi_v<T>;
  const Frame nominal = frameOf(scene.hoe.pose);
  const Eigen::Matrix<T, 3, 3> axes = nominal.axes.cast<T>();
  const V plate_origin =
      nominal.origin.cast<T>() + V(T(o.hoe_shift_mm[0]) * axes.col(0) + T(o.hoe_shift_mm[1]) * axes.col(1));
  std::vector<LayerModel> layers;
  for (const auto& l : scene.hoe_layers) layers.push_back(makeLayerModel(scene.hoe, l));
  std::vector<int> order(layers.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return layers[a].offset_um < layers[b].offset_um; });

  const V source = (toVec(scene.projector.pose.position_mm)).cast<T>() + V(T(0), T(0), T(o.source_shift_mm));
  const std::vector<ProjectorRay> grid = projectorRays(scene.projector, o.rays);
  const std::vector<double> wavelengths =
      o.wavelength_nm ? std::vector<double>{*o.wavelength_nm} : scene.projector.wavelengths_nm;
  const T half_w = T(0.5) * T(scene.hoe.size_mm[0]), half_h = T(0.5) * T(scene.hoe.size_mm[1]);
  const T n_cover = T(scene.hoe.cover_index), n_sub = T(scene.hoe.substrate_index);
  const V source_local = axes.transpose() * (source - plate_origin);
  const T n_in = source_local.z() < T(0) ? n_cover : n_sub;

  // Eye: placeEye's construction (rotationFromDeg, gazeDirection, crossPupil, fieldAngleDeg),
  // in T with the same operations.
  const std::array<double, 2> gaze = o.gaze_deg ? *o.gaze_deg : scene.eye.gaze_deg;
  const T deg = pi / T(180);
  const T r_eye = T(scene.eye.eyeball_diameter_mm) / T(2);
  const V hoe_center = nominal.origin.cast<T>();
  const V rot_center = hoe_center + V(T(scene.eye.lateral_offset_mm[0]), T(scene.eye.lateral_offset_mm[1]),
                                      -(T(scene.eye.relief_mm) + r_eye));
  const Eigen::Matrix<T, 3, 3> eye_axes =
      (Eigen::AngleAxis<T>(T(gaze[0]) * deg, V::UnitY()) * Eigen::AngleAxis<T>(-T(gaze[1]) * deg, V::UnitX()) *
       Eigen::AngleAxis<T>(T(0) * deg, V::UnitZ()))
          .toRotationMatrix();
  const V gaze_dir = eye_axes.col(2);
  const V pupil_center = rot_center + r_eye * gaze_dir;
  const T pupil_radius = T(scene.eye.pupil_diameter_mm) / T(2);

  ReferenceTrace<T> out;
  out.rays.resize(grid.size() * wavelengths.size());
  detail::FovAccumulator acc;  // comparisons only; stores doubles of the T angles
  T sum = 0;
  for (std::size_t i = 0; i < out.rays.size(); ++i) {
    const ProjectorRay& pr = grid[i % grid.size()];
    const T lambda_nm = T(wavelengths[i / grid.size()]);
    ReferenceRay<T>& r = out.rays[i];
    const V d = axes.transpose() * pr.direction.cast<T>();
    if (d.z() == T(0)) continue;
    const T t = -source_local.z() / d.z();
    if (!(t > T(0))) continue;
    const V p = source_local + t * d;
    if (abs(p.x()) > half_w || abs(p.y()) > half_h) continue;
    r.hits_hoe = true;
    T power = 1, best = -1;
    bool tir = false;
    for (std::size_t k = 0; k < order.size(); ++k) {
      const int li = d.z() > T(0) ? order[k] : order[order.size() - 1 - k];
      const LayerModel& m = layers[li];
      const RecordedGratingT<T> g = recordAtT<T>(m, p.x(), p.y());
      if (!g.valid) continue;
      const LayerDiffractionT<T> ld =
          diffractLayerT<T>(m, g.k_recorded, d, n_in, n_cover, n_sub, lambda_nm, o.polarization);
      if (!ld.entered) break;
      const T contribution = power * ld.grating.kogelnik.efficiency;
      if (ld.exits) r.efficiency += contribution;
      if (contribution > best && (ld.exits || ld.tir)) {
        best = contribution;
        r.layer = li;
        tir = ld.tir;
        r.exits = ld.exits;
        if (ld.exits) r.out_direction = axes * ld.out_dir;
      }
      power *= ld.grating.kogelnik.zero_order;
    }
    if (tir) r.exits = false;
    if (!r.exits) continue;
    // Pupil: the straight path from the plate point crosses the pupil disc.
    const V origin = plate_origin + axes * p;
    const T dn = r.out_direction.dot(gaze_dir);
    if (!(dn < T(0))) continue;
    const T tp = (pupil_center - origin).dot(gaze_dir) / dn;
    if (!(tp > T(0))) continue;
    const V cross = origin + tp * r.out_direction;
    if (!((cross - pupil_center).norm() <= pupil_radius)) continue;
    r.in_pupil = true;
    const V v = eye_axes.transpose() * (-r.out_direction.normalized());
    r.field_deg = {std::atan2(v.x(), v.z()) / deg, std::asin(std::clamp(v.y(), T(-1), T(1))) / deg};
    ++out.rays_in_pupil;
    sum += r.efficiency;
    if (r.efficiency >= T(o.efficiency_threshold)) {
      ++out.rays_efficient;
      acc.add({double(r.field_deg[0]), double(r.field_deg[1])}, (-r.out_direction).template cast<double>());
    }
  }
  // FOV in T from the extreme rays found above (yaw/pitch extremes recomputed in T).
  T yaw_min = std::numeric_limits<T>::infinity(), yaw_max = -yaw_min, pitch_min = yaw_min, pitch_max = -yaw_min;
  for (const auto& r : out.rays) {
    if (!r.in_pupil || !(r.efficiency >= T(o.efficiency_threshold))) continue;
    yaw_min = std::min(yaw_min, r.field_deg[0]);
    yaw_max = std::max(yaw_max, r.field_deg[0]);
    pitch_min = std::min(pitch_min, r.field_deg[1]);
    pitch_max = std::max(pitch_max, r.field_deg[1]);
  }
  if (out.rays_efficient > 0) out.fov_deg = {yaw_max - yaw_min, pitch_max - pitch_min, T(acc.result().diagonal)};
  out.mean_efficiency = out.rays_in_pupil ? sum / T(out.rays_in_pupil) : T(0);
  return out;
}

}  // namespace fovea

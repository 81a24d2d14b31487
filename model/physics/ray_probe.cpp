#include "model/physics/ray_probe.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include "model/physics/eye_model.h"
#include "model/physics/projector_rays.h"
#include "model/units.h"

namespace fovea {

RayProbe::RayProbe(const Scene& scene, const RayProbeSetup& setup) : polarization_(setup.polarization) {
  const Frame nominal = frameOf(scene.hoe.pose);
  plate_ = nominal;
  plate_.origin += setup.hoe_shift_mm[0] * nominal.x() + setup.hoe_shift_mm[1] * nominal.y();
  source_local_ = plate_.toLocal(projectorSource(scene.projector, setup.source_shift_mm));
  projector_axes_ = rotationFromDeg(scene.projector.pose.rotation_deg);
  half_tan_ = {std::tan(0.5 * scene.projector.fov_deg[0] * kDeg), std::tan(0.5 * scene.projector.fov_deg[1] * kDeg)};
  half_w_ = 0.5 * scene.hoe.size_mm[0];
  half_h_ = 0.5 * scene.hoe.size_mm[1];
  n_cover_ = scene.hoe.cover_index;
  n_sub_ = scene.hoe.substrate_index;
  n_in_ = source_local_.z() < 0.0 ? n_cover_ : n_sub_;
  for (const HoeLayer& l : scene.hoe_layers) layers_.push_back(makeLayerModel(scene.hoe, l));
  order_.resize(layers_.size());
  std::iota(order_.begin(), order_.end(), 0);
  std::stable_sort(order_.begin(), order_.end(),
                   [&](int a, int b) { return scene.hoe_layers[a].offset_um < scene.hoe_layers[b].offset_um; });
  eye_ = placeEye(scene, setup.gaze_deg[0], setup.gaze_deg[1]);
  eye_axes_ = rotationFromDeg({setup.gaze_deg[0], setup.gaze_deg[1], 0.0});
}

bool RayProbe::aimAt(const Eigen::Vector3d& p, std::array<double, 2>& tan_xy) const {
  const Eigen::Vector3d source = plate_.toBench(source_local_);
  const Eigen::Vector3d local = projector_axes_.transpose() * (p - source);
  if (!(local.z() > 0.0)) return false;
  tan_xy = {local.x() / local.z(), local.y() / local.z()};
  return true;
}

std::array<double, 4> RayProbe::plateBoundsTan() const {
  const std::array<double, 4> field{-half_tan_[0], half_tan_[0], -half_tan_[1], half_tan_[1]};
  std::array<double, 4> b{1e300, -1e300, 1e300, -1e300};
  for (const double u : {-half_w_, half_w_})
    for (const double v : {-half_h_, half_h_}) {
      std::array<double, 2> t;
      if (!aimAt(plate_.toBench(Eigen::Vector3d(u, v, 0.0)), t)) return field;
      b = {std::min(b[0], t[0]), std::max(b[1], t[0]), std::min(b[2], t[1]), std::max(b[3], t[1])};
    }
  return {std::max(b[0], field[0]), std::min(b[1], field[1]), std::max(b[2], field[2]), std::min(b[3], field[3])};
}

// flatten: the layer stages are inlined here (one call per ray instead of a PLT call per layer and
// stage into the interposable template copies); the same operations in the same order.
[[gnu::flatten]] ProbeRay RayProbe::trace(double tan_x, double tan_y, double wavelength_nm, ProbeAngles angles) const {
  ProbeRay out;
  // Geometry stage: the ray's direction (projectorRays()) and its hit on the plate.
  const Eigen::Vector3d direction = projector_axes_ * Eigen::Vector3d(tan_x, tan_y, 1.0).normalized();
  const Eigen::Vector3d d = plate_.axes.transpose() * direction;
  if (d.z() == 0.0) return out;
  const double t = -source_local_.z() / d.z();
  if (!(t > 0.0)) return out;
  const Eigen::Vector3d p = source_local_ + t * d;
  if (std::abs(p.x()) > half_w_ || std::abs(p.y()) > half_h_) return out;
  out.on_plate = true;
  // Diffraction, coupled wave and stack stages, layer by layer in depth order along the probe.
  const double lambda_um = wavelength_nm * 1e-3;
  const bool forward = d.z() > 0.0;
  const std::size_t nl = layers_.size();
  double power = 1.0, best = -1.0;
  bool tir = false, exits = false;
  Eigen::Vector3d out_dir = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < nl; ++k) {
    const int li = forward ? order_[k] : order_[nl - 1 - k];
    const LayerModel& m = layers_[li];
    const RecordedGrating rg = recordAt(m, p.x(), p.y());
    if (!rg.valid) continue;
    const LayerGeometryT<double> lg =
        layerGeometryT<double>(m.film, rg.k_recorded, d, n_in_, n_cover_, n_sub_, lambda_um);
    if (!lg.entered) break;  // cannot enter the stack at all
    const kogelnik::Result kr = layerCoupledWaveT<double>(m.film, lg.geometry, lambda_um, polarization_);
    const double contribution = power * kr.efficiency;
    if (lg.exits) out.efficiency += contribution;
    if (contribution > best && (lg.exits || lg.tir)) {
      best = contribution;
      tir = lg.tir;
      exits = lg.exits;
      if (lg.exits) out_dir = plate_.axes * lg.out_dir;
    }
    power *= kr.zero_order;
  }
  if (tir) exits = false;
  out.exits = exits;
  if (!exits) return out;
  // Pupil stage.
  const Eigen::Vector3d hit = plate_.toBench(p);
  const PupilCrossing c = crossPupil(eye_, hit, out_dir);
  if (!c.in_pupil) return out;
  out.in_pupil = true;
  out.field_deg = fieldAngleDeg(eye_axes_, out_dir);
  if (angles == ProbeAngles::Both) out.footprint_deg = fieldAngleDeg(eye_axes_, (eye_.pupil_center - hit).normalized());
  return out;
}

}  // namespace fovea

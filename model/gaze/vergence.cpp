#include "model/gaze/vergence.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

#include "model/scene/scene_geometry.h"
#include "model/units.h"

namespace fovea::gaze {

std::array<double, 2> gazeTowardsDeg(const Eigen::Vector3d& centre, const Eigen::Vector3d& point) {
  const Eigen::Vector3d d = point - centre;
  return {radToDeg(std::atan2(d.x(), d.z())), radToDeg(std::atan2(d.y(), std::hypot(d.x(), d.z())))};
}

FixationEstimate fixationFromGazes(const BinocularGeometry& g, const std::array<double, 2>& left_deg,
                                   const std::array<double, 2>& right_deg) {
  FixationEstimate e;
  const Eigen::Vector3d cl = g.leftCentre(), cr = g.rightCentre();
  const Eigen::Vector3d dl = gazeDirection(left_deg[0], left_deg[1]), dr = gazeDirection(right_deg[0], right_deg[1]);
  const Eigen::Vector3d n = dl.cross(dr);
  const double nn = n.squaredNorm();
  e.vergence_deg = radToDeg(std::atan2(std::sqrt(nn), dl.dot(dr)));
  if (nn < 1e-24) return e;
  const Eigen::Vector3d w = cr - cl;
  const double s = w.cross(dr).dot(n) / nn, t = w.cross(dl).dot(n) / nn;
  if (!(s > 0 && t > 0)) return e;
  const Eigen::Vector3d pl = cl + s * dl, pr = cr + t * dr;
  e.valid = true;
  e.point = 0.5 * (pl + pr);
  e.distance_mm = e.point.norm();
  e.depth_mm = e.point.z();
  e.miss_mm = (pl - pr).norm();
  return e;
}

DioptreUncertainty depthDioptreUncertainty(const BinocularGeometry& g, const std::array<double, 2>& left_deg,
                                           const std::array<double, 2>& right_deg, double sigma_left_deg,
                                           double sigma_right_deg) {
  const double k = 1000.0 / g.ipd_mm;
  const double sl = sigma_left_deg * kDeg, sr = sigma_right_deg * kDeg;
  const double tl = std::tan(left_deg[0] * kDeg), tr = std::tan(right_deg[0] * kDeg);
  const double sec2l = 1 + tl * tl, sec2r = 1 + tr * tr;
  DioptreUncertainty u;
  u.sigma_d = k * std::sqrt(sec2l * sec2l * sl * sl + sec2r * sec2r * sr * sr);
  // Yaw: the curvature of tan. Pitch (same sigma per axis): the lines pass each other at
  // heights differing by ~rho (dp_L - dp_R); the closest approach then slides both points
  // towards the eyes by rho (dp_L - dp_R)^2 / gamma^2 (gamma the horizontal vergence angle),
  // so D rises by 1000 (sigma_L^2 + sigma_R^2) / (gamma^2 Z) on average.
  const double gamma = (left_deg[0] - right_deg[0]) * kDeg;
  const double z = g.ipd_mm / (tl - tr);
  u.bias_d = k * (sec2l * tl * sl * sl - sec2r * tr * sr * sr);
  if (gamma > 0 && z > 0) u.bias_d += 1000 * (sl * sl + sr * sr) / (gamma * gamma * z);
  return u;
}

double vergenceAngleAt(const VergenceDynamics& v, double from_deg, double to_deg, double t_s) {
  const double delta = to_deg - from_deg;
  if (t_s <= 0 || delta == 0) return t_s <= 0 ? from_deg : to_deg;
  const double vmax = delta > 0 ? v.peak_convergence_deg_s : v.peak_divergence_deg_s;
  const double a = std::abs(delta), knee = vmax * v.tau_s;  // |e| where the ramp meets the exponential
  const double t_ramp = a > knee ? (a - knee) / vmax : 0.0;
  double remaining = 0;
  if (t_s < t_ramp)
    remaining = a - vmax * t_s;
  else
    remaining = std::min(a, knee) * std::exp(-(t_s - t_ramp) / v.tau_s);
  return to_deg - std::copysign(remaining, delta);
}

double vergenceForDistanceDeg(const BinocularGeometry& g, double distance_mm) {
  return 2 * radToDeg(std::atan(g.ipd_mm / 2 / distance_mm));
}

double distanceForVergenceMm(const BinocularGeometry& g, double vergence_deg) {
  return g.ipd_mm / 2 / std::tan(vergence_deg * kDeg / 2);
}

FixationDistanceFilter::FixationDistanceFilter(const BinocularGeometry& g, const VergenceDynamics& v,
                                               FixationFilterOptions o)
    : max_d_(o.max_d) {
  // Peak vergence velocity in dioptres per second: dD = d(gamma) / IPD (small angles, m).
  const double v_peak_d = std::max(v.peak_convergence_deg_s, v.peak_divergence_deg_s) * kDeg / (g.ipd_mm / 1000);
  q_ = o.q_d2_per_s3 > 0 ? o.q_d2_per_s3 : v_peak_d * v_peak_d / v.tau_s;
}

double FixationDistanceFilter::update(double t_s, double d, double sigma_d) {
  d = std::clamp(d, 0.0, max_d_);
  const double r = std::max(sigma_d * sigma_d, 1e-12);
  if (!initialised_) {
    initialised_ = true;
    t_ = t_s;
    x_ = {d, 0};
    p_ << r, 0, 0, 1e2;  // velocity unknown: (10 D/s)^2
    return d;
  }
  const double dt = std::max(0.0, t_s - t_);
  t_ = t_s;
  Eigen::Matrix2d f;
  f << 1, dt, 0, 1;
  Eigen::Matrix2d qm;
  qm << dt * dt * dt / 3, dt * dt / 2, dt * dt / 2, dt;
  x_ = f * x_;
  p_ = f * p_ * f.transpose() + q_ * qm;
  const double s = p_(0, 0) + r;
  const Eigen::Vector2d k = p_.col(0) / s;
  const double innovation = d - x_[0];
  x_ += k * innovation;
  p_ = (Eigen::Matrix2d::Identity() - k * Eigen::RowVector2d(1, 0)) * p_;
  return x_[0];
}

}  // namespace fovea::gaze

#include "model/physics/hologram_astigmatism.h"

#include <cmath>

#include <Eigen/Dense>

namespace fovea {

namespace {
// E^T (I - v v^T) E for the plate basis E: the plate-restricted transverse projector.
Eigen::Matrix2d plateProjector(const HologramPointGeometry& g, const Eigen::Vector3d& v) {
  Eigen::Matrix<double, 3, 2> e;
  e.col(0) = g.plate_x;
  e.col(1) = g.plate_y;
  const Eigen::Vector2d vt = e.transpose() * v;
  return Eigen::Matrix2d::Identity() - vt * vt.transpose();
}
}  // namespace

Eigen::Vector3d hologramOutDirection(const HologramPointGeometry& g, const Eigen::Vector3d& u_in,
                                     const Eigen::Vector3d& eye_side) {
  const Eigen::Vector3d r = (g.point - g.reference_mm).normalized();  // reference, diverging
  const Eigen::Vector3d s = (g.signal_mm - g.point).normalized();     // signal, converging
  const Eigen::Vector3d n = g.plate_x.cross(g.plate_y).normalized();
  auto tangential = [&](const Eigen::Vector3d& v) { return Eigen::Vector3d(v - v.dot(n) * n); };
  const Eigen::Vector3d out_t = tangential(u_in) + g.mu * (tangential(s) - tangential(r));
  const double t2 = out_t.squaredNorm();
  if (!(t2 < 1.0)) return Eigen::Vector3d::Zero();
  const double side = eye_side.dot(n) >= 0 ? 1.0 : -1.0;
  return out_t + side * std::sqrt(1.0 - t2) * n;
}

Eigen::Matrix2cd hologramOutputCurvature(const HologramPointGeometry& g, const Eigen::Vector3d& u_in,
                                         std::complex<double> q_in, const Eigen::Vector3d& /*u_out*/,
                                         const Eigen::Matrix<double, 3, 2>& out_basis) {
  const double l_r = (g.point - g.reference_mm).norm(), l_s = (g.signal_mm - g.point).norm();
  const Eigen::Vector3d r = (g.point - g.reference_mm) / l_r, s = (g.signal_mm - g.point) / l_s;
  // H_out = E^T Q_in^-1 E - mu (E^T P_s E / L_s + E^T P_r E / L_r)  (header).
  const Eigen::Matrix2cd h_out =
      plateProjector(g, u_in).cast<std::complex<double>>() / q_in -
      (g.mu * (plateProjector(g, s) / l_s + plateProjector(g, r) / l_r)).cast<std::complex<double>>();
  Eigen::Matrix<double, 3, 2> e;
  e.col(0) = g.plate_x;
  e.col(1) = g.plate_y;
  const Eigen::Matrix2d t = out_basis.transpose() * e;  // T = B^T E
  const Eigen::Matrix2d t_inv = t.inverse();
  return t_inv.transpose().cast<std::complex<double>>() * h_out * t_inv.cast<std::complex<double>>();
}

}  // namespace fovea

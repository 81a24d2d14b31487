#include "model/analysis/hoe_focus.h"

#include <cmath>

#include <Eigen/Eigenvalues>

#include "model/physics/trace.h"

namespace fovea {

std::optional<LeastSquaresFocus> leastSquaresFocus(const std::vector<Eigen::Vector3d>& origins,
                                                   const std::vector<Eigen::Vector3d>& directions) {
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  int n = 0;
  for (std::size_t i = 0; i < origins.size() && i < directions.size(); ++i) {
    const double len = directions[i].norm();
    if (!(len > 0)) continue;
    const Eigen::Vector3d d = directions[i] / len;
    const Eigen::Matrix3d p = Eigen::Matrix3d::Identity() - d * d.transpose();  // onto the plane normal to d
    a += p;
    b += p * origins[i];
    ++n;
  }
  if (n < 2) return std::nullopt;
  // Singular when all rays are parallel: the smallest eigenvalue of A is then 0 (each term has
  // eigenvalues 1, 1, 0; n rays give a trace of 2n).
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(a);
  if (!(eig.eigenvalues().minCoeff() > 1e-10 * n)) return std::nullopt;
  LeastSquaresFocus out;
  out.point = a.ldlt().solve(b);
  double sum = 0;
  for (std::size_t i = 0; i < origins.size() && i < directions.size(); ++i) {
    const double len = directions[i].norm();
    if (!(len > 0)) continue;
    const Eigen::Vector3d d = directions[i] / len;
    const Eigen::Vector3d r = out.point - origins[i];
    sum += (r - d * d.dot(r)).squaredNorm();
  }
  out.rms_distance_mm = std::sqrt(sum / n);
  return out;
}

std::optional<HoeFocus> hoeFocus(const Scene& scene, std::array<double, 2> hoe_shift_mm,
                                 const HoeFocusOptions& options) {
  TraceOptions o;
  o.hoe_shift_mm = hoe_shift_mm;
  o.rays = options.rays;
  o.wavelength_nm = options.wavelength_nm;
  o.efficiency_threshold = options.efficiency_threshold;
  const std::vector<TracedRay> rays = diffractScene(scene, o);
  std::vector<Eigen::Vector3d> origins, directions;
  origins.reserve(rays.size());
  directions.reserve(rays.size());
  for (const TracedRay& r : rays) {
    if (!r.hits_hoe || !r.exits || !r.towards_eye || r.evanescent || r.tir) continue;
    if (!(r.efficiency >= options.efficiency_threshold)) continue;
    origins.push_back(r.hoe_point);
    directions.push_back(r.out_direction);
  }
  const auto f = leastSquaresFocus(origins, directions);
  if (!f) return std::nullopt;
  return HoeFocus{*f, static_cast<int>(origins.size())};
}

}  // namespace fovea

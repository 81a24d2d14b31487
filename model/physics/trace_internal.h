#pragma once
// Pieces shared by trace.cpp and trace_pipeline.cpp (not part of the public API).

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "model/physics/trace.h"

namespace fovea::detail {

struct FovAccumulator {
  double yaw_min = std::numeric_limits<double>::infinity(), yaw_max = -yaw_min;
  double pitch_min = yaw_min, pitch_max = -yaw_min;
  double sum_max = -yaw_min, sum_min = yaw_min, diff_max = -yaw_min, diff_min = yaw_min;
  Eigen::Vector3d d_sum_max = Eigen::Vector3d::Zero(), d_sum_min = d_sum_max, d_diff_max = d_sum_max,
                  d_diff_min = d_sum_max;  // set by the first add()
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

inline std::vector<double> tracedWavelengths(const Scene& scene, const TraceOptions& o) {
  if (o.wavelength_nm) return {*o.wavelength_nm};
  return scene.projector.wavelengths_nm;
}

}  // namespace fovea::detail

#pragma once
// The eye as the trace sees it (seed A.3): a 23 mm eyeball rotating about its centre, a 5 mm
// pupil disc on its surface normal to the gaze, visual angles measured from the gaze axis.

#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/Core>

#include "model/scene/scene_geometry.h"
#include "model/units.h"

namespace fovea {

// Does the ray origin + t dir (t > 0, travelling into the eye) cross the pupil disc?
struct PupilCrossing {
  bool in_pupil = false;
  double radius_mm = 0.0;                           // distance from the pupil centre in its plane
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // crossing of the pupil plane
};
PupilCrossing crossPupil(const EyePlacement& eye, const Eigen::Vector3d& origin, const Eigen::Vector3d& dir);

// Visual angle of light arriving along `dir` (bench) for an eye with the given axes
// (rotationFromDeg(gaze yaw, gaze pitch, 0)): the direction the light comes from, -dir, in the
// eye frame as (yaw, pitch) with the same convention as gazeDirection():
//   yaw = atan2(x, z), pitch = asin(y)  (degrees; yaw > 0 towards the eye's +x, pitch > 0 up).
// Inline: the ray probe's inner loop calls it for every ray entering the pupil.
inline std::array<double, 2> fieldAngleDeg(const Eigen::Matrix3d& eye_axes, const Eigen::Vector3d& dir) {
  const Eigen::Vector3d v = eye_axes.transpose() * (-dir.normalized());
  return {std::atan2(v.x(), v.z()) / kDeg, std::asin(std::clamp(v.y(), -1.0, 1.0)) / kDeg};
}

}  // namespace fovea

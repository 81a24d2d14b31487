#include "model/physics/eye_model.h"

#include <algorithm>
#include <cmath>

#include "model/units.h"

namespace fovea {

PupilCrossing crossPupil(const EyePlacement& eye, const Eigen::Vector3d& origin, const Eigen::Vector3d& dir) {
  PupilCrossing c;
  const double dn = dir.dot(eye.gaze);
  if (!(dn < 0.0)) return c;  // not travelling into the eye
  const double t = (eye.pupil_center - origin).dot(eye.gaze) / dn;
  if (!(t > 0.0)) return c;
  c.point = origin + t * dir;
  c.radius_mm = (c.point - eye.pupil_center).norm();
  c.in_pupil = c.radius_mm <= eye.pupil_radius_mm;
  return c;
}

}  // namespace fovea

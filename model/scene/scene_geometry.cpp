#include "model/scene/scene_geometry.h"

#include <cmath>

#include "model/units.h"

namespace fovea {

namespace {}

Eigen::Matrix3d rotationFromDeg(const std::array<double, 3>& ypr) {
  // Pitch > 0 must lift +z towards +y: a rotation about +x by -pitch (right-hand rule).
  return (Eigen::AngleAxisd(ypr[0] * kDeg, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(-ypr[1] * kDeg, Eigen::Vector3d::UnitX()) *
          Eigen::AngleAxisd(ypr[2] * kDeg, Eigen::Vector3d::UnitZ()))
      .toRotationMatrix();
}

Frame frameOf(const Pose& pose) {
  Frame f;
  f.origin = toVec(pose.position_mm);
  f.axes = rotationFromDeg(pose.rotation_deg);
  return f;
}

Eigen::Vector3d gazeDirection(double yaw_deg, double pitch_deg) {
  return rotationFromDeg({yaw_deg, pitch_deg, 0.0}).col(2);
}

EyePlacement placeEye(const Scene& scene, double yaw_deg, double pitch_deg) {
  EyePlacement e;
  e.eyeball_radius_mm = scene.eye.eyeball_diameter_mm / 2.0;
  e.pupil_radius_mm = scene.eye.pupil_diameter_mm / 2.0;
  const Eigen::Vector3d hoe = toVec(scene.hoe.pose.position_mm);
  e.rotation_center = hoe + Eigen::Vector3d(scene.eye.lateral_offset_mm[0], scene.eye.lateral_offset_mm[1],
                                            -(scene.eye.relief_mm + e.eyeball_radius_mm));
  e.gaze = gazeDirection(yaw_deg, pitch_deg);
  e.pupil_center = e.rotation_center + e.eyeball_radius_mm * e.gaze;
  return e;
}

EyePlacement placeEye(const Scene& scene) {
  return placeEye(scene, scene.eye.gaze_deg[0], scene.eye.gaze_deg[1]);
}

}  // namespace fovea

#pragma once
// Frames of the scene's elements in the bench frame (see scene.h for conventions).

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "model/scene/scene.h"

namespace fovea {

// Rotation taking element-local axes to bench axes: R = Ry(yaw) * Rx(pitch) * Rz(roll).
// Signs: yaw > 0 turns local +z towards bench +x; pitch > 0 turns local +z towards bench +y
// (so a pitch of +10 deg looks up), roll > 0 turns local +x towards +y.
Eigen::Matrix3d rotationFromDeg(const std::array<double, 3>& yaw_pitch_roll_deg);

inline Eigen::Vector3d toVec(const Vec3mm& v) {
  return {v[0], v[1], v[2]};
}
inline Vec3mm fromVec(const Eigen::Vector3d& v) {
  return {v.x(), v.y(), v.z()};
}

struct Frame {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();  // columns: local x, y, z in bench
  Eigen::Vector3d x() const { return axes.col(0); }
  Eigen::Vector3d y() const { return axes.col(1); }
  Eigen::Vector3d z() const { return axes.col(2); }
  Eigen::Vector3d toBench(const Eigen::Vector3d& local) const { return origin + axes * local; }
  Eigen::Vector3d toLocal(const Eigen::Vector3d& bench) const { return axes.transpose() * (bench - origin); }
};

Frame frameOf(const Pose& pose);

// Unit direction of a gaze (yaw, pitch in degrees) in the bench frame: yaw about +y towards
// +x, then pitch up. Zero gaze looks along +z.
Eigen::Vector3d gazeDirection(double yaw_deg, double pitch_deg);

// The eye in the bench frame. The rotation centre sits (relief + eyeball radius) behind the
// HOE's nominal centre along -z, decentred by lateral_offset_mm; the pupil centre lies on
// the eyeball surface along the gaze direction.
struct EyePlacement {
  Eigen::Vector3d rotation_center;
  Eigen::Vector3d gaze;  // unit optical axis
  Eigen::Vector3d pupil_center;
  double pupil_radius_mm = 2.5;
  double eyeball_radius_mm = 11.5;
};
EyePlacement placeEye(const Scene& scene);
EyePlacement placeEye(const Scene& scene, double yaw_deg, double pitch_deg);

}  // namespace fovea

#include "model/gaze/pupil_camera.h"

#include "model/scene/scene_geometry.h"

namespace fovea::gaze {

Eigen::Vector2d pupilCentrePx(const PupilCamera& c, double yaw_deg, double pitch_deg) {
  const Eigen::Vector3d p = c.pupil_distance_mm * gazeDirection(yaw_deg, pitch_deg);  // from the rotation centre
  const double z = c.camera_distance_mm - p.z();
  return {c.principal_px.x() + c.focal_px * p.x() / z, c.principal_px.y() - c.focal_px * p.y() / z};
}

}  // namespace fovea::gaze

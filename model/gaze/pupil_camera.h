#pragma once
// A pinhole pupil camera on the visual axis facing the eye (the seed's on-axis pupil
// tracking, Fig. S23): where the pupil centre appears in the camera image for a gaze.
// Used to synthesise calibration samples (tests, demos); real samples come from the
// pupil detector.
//
// The pupil centre sits `pupil_distance_mm` from the eye's rotation centre along the gaze
// (gazeDirection of scene_geometry.h); the camera's pinhole lies `camera_distance_mm` in
// front of the rotation centre on the zero-gaze axis, looking back at the eye. Image x
// grows with the eye's +x (no mirror), image y grows downwards (pitch up = smaller y).

#include <Eigen/Core>

namespace fovea::gaze {

struct PupilCamera {
  double focal_px = 600;                       // focal length in pixels
  Eigen::Vector2d principal_px{320.0, 240.0};  // principal point
  double camera_distance_mm = 35;              // rotation centre to pinhole
  double pupil_distance_mm = 10.5;             // rotation centre to pupil centre
};

// Perspective projection of the pupil centre: x = c_x + f X/Z, y = c_y - f Y/Z with
// (X, Y) the lateral pupil offset and Z its distance from the pinhole along the axis.
Eigen::Vector2d pupilCentrePx(const PupilCamera& camera, double yaw_deg, double pitch_deg);

}  // namespace fovea::gaze

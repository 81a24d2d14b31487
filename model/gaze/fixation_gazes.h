#pragma once
// The two gazes that fixate a point (issue 30 item 5): vergence the other way round.
//
// Head frame and gaze angles as model/gaze/vergence.h (origin midway between the rotation
// centres c_L = (-IPD/2, 0, 0) and c_R = (+IPD/2, 0, 0), Fick (yaw, pitch) in degrees,
// d(y, p) = (cos p sin y, sin p, cos p cos y)).
//
// gazesFixating: the fixation point at cyclopean distance D in the direction (y, p) seen from
// the head origin is P = D d(y, p); each eye's gaze is the direction from its centre to P
// (gazeTowardsDeg). Exact: fixationFromGazes of the two gazes returns P (to rounding).
//
// fixationOnRightGaze: the point at cyclopean distance D on the right eye's line of sight
// c_R + t d_R (t > 0): |c_R + t d_R| = D gives t^2 + 2 b t + |c_R|^2 - D^2 = 0 with
// b = c_R . d_R, so t = -b + sqrt(b^2 + D^2 - |c_R|^2) (the positive root; D > IPD/2 makes
// the discriminant exceed b^2, and the square root is ~D, far from cancelling b). Then the
// gazes as above. The two functions invert each other: the direction of
// fixationOnRightGaze(right gaze of gazesFixating(y, p, D), D).point is (y, p).
//
// A binocular scene keeps the right eye's gaze (eye.gaze_deg) and the fixation distance
// (binocular.fixation_distance_mm); model/scene/eye_scene.h derives the left eye's gaze with
// fixationOnRightGaze. Pure functions.

#include <array>

#include <Eigen/Core>

#include "model/gaze/vergence.h"

namespace fovea::gaze {

struct FixationGazes {
  std::array<double, 2> left_deg{0, 0};       // left eye's (yaw, pitch), head frame
  std::array<double, 2> right_deg{0, 0};      // right eye's
  std::array<double, 2> direction_deg{0, 0};  // of the point from the head origin
  Eigen::Vector3d point{0, 0, 0};             // the fixation point (mm, head frame)
  double distance_mm = 0;                     // |point|
  double vergence_deg = 0;                    // angle between the two lines of sight
};

// Requires distance_mm > IPD/2 (std::invalid_argument otherwise).
FixationGazes gazesFixating(const BinocularGeometry& g, const std::array<double, 2>& direction_deg, double distance_mm);
FixationGazes fixationOnRightGaze(const BinocularGeometry& g, const std::array<double, 2>& right_deg,
                                  double distance_mm);

}  // namespace fovea::gaze

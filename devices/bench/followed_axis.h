#pragma once
// One simulated stage axis driven like TargetFollower (devices/bench/): a move to the latest
// target starts when the previous one ends; targets within the deadband of the last one are
// ignored. Used by the closed gaze loop and the binocular focus loop.
#include <cmath>
#include <optional>

#include "devices/virtual/motion_profile.h"

namespace fovea::devices {

class FollowedAxis {
 public:
  FollowedAxis(double v_max, double accel, double deadband, double start = 0)
      : v_(v_max), a_(accel), deadband_(deadband), profile_(MotionProfile::rest(0, start)), last_(start) {}
  void command(double t, double target) {
    advance(t);
    if (std::abs(target - last_) <= deadband_) {
      pending_.reset();
      return;
    }
    if (profile_.activeAt(t)) {
      pending_ = target;
      return;
    }
    start(t, target);
  }
  void advance(double t) {
    if (pending_ && profile_.endTime() <= t) {
      start(profile_.endTime(), *pending_);
      pending_.reset();
    }
  }
  double position(double t) {
    advance(t);
    return profile_.position(t);
  }
  double busyUntil() const { return profile_.endTime(); }
  bool pending() const { return pending_.has_value(); }

 private:
  void start(double t, double target) {
    profile_ = MotionProfile::trapezoid(t, profile_.position(t), target, v_, a_);
    last_ = target;
  }
  double v_, a_, deadband_;
  MotionProfile profile_;
  double last_ = 0;
  std::optional<double> pending_;
};

}  // namespace fovea::devices

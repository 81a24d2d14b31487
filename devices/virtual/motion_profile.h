#pragma once
// Motion of one simulated axis as constant-acceleration segments: trapezoidal point-to-point
// moves (accelerate at a to v_max, cruise, decelerate at a; a triangle when the distance is
// shorter than v_max^2/a) and decelerating stops. Pure functions of time.
#include <vector>

namespace fovea::devices {

struct MotionSegment {
  double t0 = 0, x0 = 0, v0 = 0, a = 0, duration = 0;  // x(t) = x0 + v0 (t-t0) + a (t-t0)^2 / 2
};

class MotionProfile {
 public:
  MotionProfile() = default;
  // At rest at x_from at time t0, move to x_to with speed limit v_max > 0 and acceleration a > 0.
  static MotionProfile trapezoid(double t0, double x_from, double x_to, double v_max, double a);
  // Moving with velocity v at x at time t0: decelerate at a to rest.
  static MotionProfile decelerate(double t0, double x, double v, double a);
  static MotionProfile rest(double t0, double x);

  double position(double t) const;
  double velocity(double t) const;
  double endTime() const;
  double endPosition() const;
  bool activeAt(double t) const { return t < endTime(); }

 private:
  std::vector<MotionSegment> segments_;
  double t_start_ = 0, x_rest_ = 0;
};

}  // namespace fovea::devices

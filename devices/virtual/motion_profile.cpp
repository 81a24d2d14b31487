#include "devices/virtual/motion_profile.h"

#include <cmath>

namespace fovea::devices {

MotionProfile MotionProfile::rest(double t0, double x) {
  MotionProfile p;
  p.t_start_ = t0;
  p.x_rest_ = x;
  return p;
}

MotionProfile MotionProfile::trapezoid(double t0, double x_from, double x_to, double v_max, double a) {
  MotionProfile p = rest(t0, x_from);
  const double d = std::abs(x_to - x_from);
  if (d <= 0 || v_max <= 0 || a <= 0) {
    p.x_rest_ = x_to;
    return p;
  }
  const double s = x_to > x_from ? 1.0 : -1.0;
  // Peak speed: v_max if the acceleration distance v^2/(2a) twice fits in d, else sqrt(a d).
  const double v_peak = std::min(v_max, std::sqrt(a * d));
  const double t_acc = v_peak / a;
  const double d_acc = 0.5 * a * t_acc * t_acc;
  const double t_cruise = (d - 2 * d_acc) / v_peak;
  double t = t0, x = x_from;
  p.segments_.push_back({t, x, 0.0, s * a, t_acc});
  t += t_acc;
  x += s * d_acc;
  if (t_cruise > 0) {
    p.segments_.push_back({t, x, s * v_peak, 0.0, t_cruise});
    t += t_cruise;
    x += s * v_peak * t_cruise;
  }
  p.segments_.push_back({t, x, s * v_peak, -s * a, t_acc});
  p.x_rest_ = x_to;
  return p;
}

MotionProfile MotionProfile::decelerate(double t0, double x, double v, double a) {
  MotionProfile p = rest(t0, x);
  if (v == 0 || a <= 0) return p;
  const double s = v > 0 ? 1.0 : -1.0;
  const double t_stop = std::abs(v) / a;
  p.segments_.push_back({t0, x, v, -s * a, t_stop});
  p.x_rest_ = x + v * t_stop / 2;
  return p;
}

double MotionProfile::position(double t) const {
  if (segments_.empty() || t >= endTime()) return x_rest_;
  if (t <= t_start_) return segments_.front().x0;
  for (const auto& g : segments_) {
    if (t < g.t0 + g.duration) {
      const double dt = t - g.t0;
      return g.x0 + g.v0 * dt + 0.5 * g.a * dt * dt;
    }
  }
  return x_rest_;
}

double MotionProfile::velocity(double t) const {
  if (segments_.empty() || t >= endTime() || t < t_start_) return 0.0;
  for (const auto& g : segments_)
    if (t < g.t0 + g.duration) return g.v0 + g.a * (t - g.t0);
  return 0.0;
}

double MotionProfile::endTime() const {
  if (segments_.empty()) return t_start_;
  const auto& g = segments_.back();
  return g.t0 + g.duration;
}

double MotionProfile::endPosition() const {
  return x_rest_;
}

}  // namespace fovea::devices

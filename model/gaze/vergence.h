#pragma once
// Vergence from two tracked gazes (issue 30; seed C.4: "A binocular version of the eye tracker
// can be used to compute vergence from both eyes").
//
// Head frame: origin midway between the eyes' rotation centres, +x towards the right eye, +y
// up, +z straight ahead; the left eye's centre at (-IPD/2, 0, 0), the right's at (+IPD/2, 0, 0)
// (default IPD 63 mm). Gazes are (yaw, pitch) in degrees as scene_geometry.h's gazeDirection:
// d = (cos p sin y, sin p, cos p cos y) (Fick: yaw about +y, then pitch). The line of sight
// passes through the rotation centre (the pupil sits on it, eyeball radius in front).
//
// Fixation point: the closest approach of the two lines of sight c_L + s d_L, c_R + t d_R,
// with n = d_L x d_R and w = c_R - c_L:
//   s = ((w x d_R) . n) / |n|^2,  t = ((w x d_L) . n) / |n|^2
// (written with the cross product rather than 1 - (d_L . d_R)^2, which cancels at far
// fixations where the lines are nearly parallel); the fixation point is the midpoint of the
// two closest points, `miss_mm` their separation (zero for exact gazes).
//
// Uncertainty (closed form, first order). With Fick angles tan(yaw) = x/z on each line of
// sight, so for a fixation at depth Z (the z of the point, measured from the rotation
// centres' plane): tan y_L = (X + IPD/2)/Z and tan y_R = (X - IPD/2)/Z, hence
//   D = 1000/Z = 1000 (tan y_L - tan y_R) / IPD      (dioptres, Z and IPD in mm),
// exactly, and D is linear in tan(yaw). Independent yaw errors of standard deviation
// sigma_L, sigma_R (radians) give
//   sigma_D^2 = (1000/IPD)^2 (sec^4 y_L sigma_L^2 + sec^4 y_R sigma_R^2)
//   bias_D    = (1000/IPD) (sec^2 y_L tan y_L sigma_L^2 - sec^2 y_R tan y_R sigma_R^2)  (2nd order)
// Pitch errors move the lines out of the plane they span (for small vergence angles that
// plane contains both lines' horizontal yaw derivative), so they enter the depth only at
// second order: the lines pass each other at heights differing by h = rho (dp_L - dp_R)
// (rho the range), and the closest approach of two lines crossing at the small angle gamma
// slides towards the eyes by about h (dp_L - dp_R) / gamma^2, a bias
//   bias_D += 1000 (sigma_pL^2 + sigma_pR^2) / (gamma^2 Z)   (gamma = y_L - y_R, radians)
// (2000 sigma^2 Z / IPD^2 straight ahead: 0.0012 D at 80 cm for 0.1 deg), whose spread adds
// in quadrature below 1 % of sigma_D at 250 cm. The Monte-Carlo test
// (tests/model/tst_vergence.cpp) checks sigma_D and the bias with noise on both axes. In
// dioptres the noise hardly depends on the distance (sec^4 near 1), which is why the
// fixation filter below works in dioptres.
//
// Eye dynamics (the simulated eyes of the binocular closed loop): a vergence step after the
// movement onset is a rate-limited first-order response of the vergence angle: the remaining
// error e decays as de/dt = -min(|e|/tau, v_peak) (C1: ramp at v_peak while |e| > v_peak tau,
// then exponential with time constant tau). tau = 0.15 s; v_peak 69 deg/s converging and
// 53 deg/s diverging (the fastest vergence velocities reported, proximal vergence of
// ~4 deg: a hard case for the display); latency from a stimulus to the movement onset
// 0.16 s (Rashbass & Westheimer 1961). Sources and what is not modelled: docs/references.md
// and docs/gaze-tracking.md ("Vergence and the focus loop").
//
// Fixation-distance filter: a constant-velocity Kalman filter on D (dioptres) with
// continuous white-noise acceleration of spectral density q = v_peak_D^2 / tau (v_peak_D the
// eye's peak vergence velocity in dioptres per second: the largest change of velocity the
// eye makes within one time constant), and the measurement variance of the closed form. The
// constant-velocity model follows a vergence ramp without steady lag; measurements outside
// [0, max_d] (diverging or crossing-behind lines) are clamped.

#include <array>
#include <optional>

#include <Eigen/Core>

namespace fovea::gaze {

struct BinocularGeometry {
  double ipd_mm = 63.0;
  Eigen::Vector3d leftCentre() const { return {-ipd_mm / 2, 0, 0}; }
  Eigen::Vector3d rightCentre() const { return {ipd_mm / 2, 0, 0}; }
};

// (yaw, pitch) in degrees of the line of sight from `centre` through `point` (Fick).
std::array<double, 2> gazeTowardsDeg(const Eigen::Vector3d& centre, const Eigen::Vector3d& point);

struct FixationEstimate {
  bool valid = false;  // false: parallel or diverging lines (no point in front)
  Eigen::Vector3d point{0, 0, 0};
  double distance_mm = 0;   // from the head-frame origin (cyclopean distance)
  double depth_mm = 0;      // z of the point (from the rotation centres' plane)
  double miss_mm = 0;       // separation of the two closest points
  double vergence_deg = 0;  // angle between the two lines of sight
};
FixationEstimate fixationFromGazes(const BinocularGeometry& g, const std::array<double, 2>& left_deg,
                                   const std::array<double, 2>& right_deg);

struct DioptreUncertainty {
  double sigma_d = 0;  // standard deviation of D = 1000/depth
  double bias_d = 0;   // second-order mean error
};
// Closed form above; sigma_*_deg the per-eye yaw noise (standard deviation, degrees).
DioptreUncertainty depthDioptreUncertainty(const BinocularGeometry& g, const std::array<double, 2>& left_deg,
                                           const std::array<double, 2>& right_deg, double sigma_left_deg,
                                           double sigma_right_deg);

struct VergenceDynamics {
  double latency_s = 0.16;  // stimulus to movement onset (not part of the display loop)
  double tau_s = 0.15;
  double peak_convergence_deg_s = 69.0, peak_divergence_deg_s = 53.0;
};
// Vergence angle `t_s` after the onset of a step from `from_deg` to `to_deg` (t < 0: from).
double vergenceAngleAt(const VergenceDynamics& v, double from_deg, double to_deg, double t_s);
// Vergence angle (degrees) of a point at cyclopean distance `distance_mm` straight ahead, and back.
double vergenceForDistanceDeg(const BinocularGeometry& g, double distance_mm);
double distanceForVergenceMm(const BinocularGeometry& g, double vergence_deg);

struct FixationFilterOptions {
  double q_d2_per_s3 = 0;  // 0: from the dynamics (v_peak_D^2 / tau)
  double max_d = 5.0;      // measurement clamp (20 cm)
};

class FixationDistanceFilter {
 public:
  FixationDistanceFilter(const BinocularGeometry& g, const VergenceDynamics& v, FixationFilterOptions o = {});
  // A measurement at time t_s of D (dioptres) with standard deviation sigma_d. Returns the
  // filtered D.
  double update(double t_s, double d, double sigma_d);
  std::optional<double> estimate() const { return initialised_ ? std::optional<double>(x_[0]) : std::nullopt; }
  double velocity() const { return x_[1]; }
  double q() const { return q_; }

 private:
  double q_, max_d_;
  bool initialised_ = false;
  double t_ = 0;
  Eigen::Vector2d x_{0, 0};
  Eigen::Matrix2d p_ = Eigen::Matrix2d::Zero();
};

}  // namespace fovea::gaze

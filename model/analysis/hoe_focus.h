#pragma once
// The focus of the rays leaving the HOE towards the eye, in the least-squares sense, and the
// seed's x_p rule built on it (gaze_studies.h, XpRule::FollowFocus): "move the HOE until the
// diffracted rays' focus lies on the rotated pupil centre" (supplement A.3/A.4, Fig. S5).
//
// Least-squares focus of rays (o_i, d_i), d_i unit: the point P minimising
//   sum_i |(I - d_i d_i^T)(P - o_i)|^2,
// the sum of squared perpendicular distances from P to the rays ((I - d d^T) projects onto the
// plane normal to d). Its gradient vanishes at the normal equations
//   [sum_i (I - d_i d_i^T)] P = sum_i (I - d_i d_i^T) o_i,
// a 3x3 symmetric positive semi-definite system, singular only when every ray is parallel to
// one direction (then no point is singled out). For rays through one point Q every term
// (I - d d^T)(Q - o_i) vanishes, so P = Q exactly.

#include <array>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "model/scene/scene.h"

namespace fovea {

struct LeastSquaresFocus {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  double rms_distance_mm = 0;  // root-mean-square distance of the rays from `point`
};

// nullopt when the system is singular (fewer than two non-parallel rays). Directions need not
// be unit (they are normalised); zero directions are skipped.
std::optional<LeastSquaresFocus> leastSquaresFocus(const std::vector<Eigen::Vector3d>& origins,
                                                   const std::vector<Eigen::Vector3d>& directions);

struct HoeFocusOptions {
  int rays = 1500;                      // projector rays per wavelength (diffractScene)
  double efficiency_threshold = 0.1;    // only rays the eye would see lit count
  std::optional<double> wavelength_nm;  // default: every projector laser, pooled
};

struct HoeFocus {
  LeastSquaresFocus focus;
  int rays = 0;  // rays that entered the sum
};

// The least-squares focus of the rays that leave the HOE towards the eye (they hit the plate,
// some order exits the stack towards the eye side, efficiency >= threshold), from their plate
// points along their directions, with the plate shifted by hoe_shift_mm (HOE local x, y; the
// fringes move with it, trace.h). Gaze-independent. nullopt when fewer than two such rays.
std::optional<HoeFocus> hoeFocus(const Scene& scene, std::array<double, 2> hoe_shift_mm,
                                 const HoeFocusOptions& options = {});

}  // namespace fovea

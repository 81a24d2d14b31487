#pragma once
// One projector ray at a chosen angle, traced through the HOE stack to the eye: the same
// model and the same floating-point operations as one ray of the trace pipeline
// (trace_pipeline.h: geometry -> recording -> diffraction -> coupled wave -> stack -> pupil),
// without its grid, memo tables or per-ray storage. The exact FOV estimator
// (model/analysis/fov_edges.h) root-finds the field's edges with it; tests check it returns
// the pipeline's values at the pipeline's own grid rays.
//
// A projector ray is addressed by its image-plane coordinates (tan of the horizontal and
// vertical angle from the projector axis, projector_rays.h): the grid rays sit at
//   tan_x = tan(fov_h / 2) ((2 ix + 1) / nx - 1),   tan_y likewise.

#include <array>
#include <vector>

#include <Eigen/Core>

#include "model/physics/grating.h"
#include "model/physics/hoe_recording.h"
#include "model/scene/scene.h"
#include "model/scene/scene_geometry.h"

namespace fovea {

struct RayProbeSetup {
  std::array<double, 2> gaze_deg{0, 0};          // yaw, pitch
  std::array<double, 2> hoe_shift_mm{0.0, 0.0};  // lateral HOE shift (HOE local x, y)
  double source_shift_mm = 0.0;                  // projector point-source shift along bench z
  Polarization polarization = Polarization::Unpolarized;
};

struct ProbeRay {
  bool on_plate = false;  // meets the plate inside its aperture
  bool exits = false;     // some layer's diffracted order leaves the stack (not TIR)
  bool in_pupil = false;
  double efficiency = 0;                  // summed over the layers (as TracedRay::efficiency)
  std::array<double, 2> field_deg{0, 0};  // visual angle (yaw, pitch) when in_pupil
  // When in_pupil: the direction (yaw, pitch, eye frame) in which the eye's pupil centre sees
  // the ray's plate point, whatever the ray's own direction: the lit footprint on the plate as
  // seen from the pupil (how the seed measures the peripheral FOV, C.2 and Fig. S5).
  std::array<double, 2> footprint_deg{0, 0};
};

// Which visual angles trace() fills for a ray entering the pupil: both (the default), or only
// field_deg when the caller never reads footprint_deg (saves two atan2/asin per ray; the values
// it does fill are the same).
enum class ProbeAngles { Both, FieldOnly };

class RayProbe {
 public:
  RayProbe(const Scene& scene, const RayProbeSetup& setup);

  ProbeRay trace(double tan_x, double tan_y, double wavelength_nm, ProbeAngles angles = ProbeAngles::Both) const;

  // Half-extent of the projector image plane: tan(fov / 2) horizontally and vertically.
  std::array<double, 2> halfTan() const { return half_tan_; }
  const EyePlacement& eye() const { return eye_; }
  // The image-plane point (tan_x, tan_y) whose ray meets the plate plane at bench point p
  // (false if p is behind the projector).
  bool aimAt(const Eigen::Vector3d& p, std::array<double, 2>& tan_xy) const;
  // The image-plane box (tan_x lo, hi, tan_y lo, hi) outside which no ray meets the plate:
  // the bounds of its corners' images (a plane quadrilateral maps to the convex hull of its
  // corners' images), clipped to the projector field; the whole field when a corner is behind
  // the projector.
  std::array<double, 4> plateBoundsTan() const;

 private:
  Frame plate_;
  Eigen::Vector3d source_local_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d projector_axes_ = Eigen::Matrix3d::Identity();
  std::array<double, 2> half_tan_{0, 0};
  double half_w_ = 0, half_h_ = 0, n_in_ = 1, n_cover_ = 1, n_sub_ = 1;
  std::vector<LayerModel> layers_;
  std::vector<int> order_;  // layer indices by depth (offset_um)
  EyePlacement eye_;
  Eigen::Matrix3d eye_axes_ = Eigen::Matrix3d::Identity();
  Polarization polarization_ = Polarization::Unpolarized;
};

}  // namespace fovea

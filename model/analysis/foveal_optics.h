#pragma once
// Optical limit of the foveal image combiner by real ray tracing (supplement A.5.1, Fig. S7).
//
// The combiner is modelled as the simple on-axis magnifier the seed describes: a concave
// spherical mirror (unfolded; the beam splitter only folds the path) at b = eye_distance_mm
// in front of the zero-gaze pupil, with the micro-OLED inside its focal length so that its
// virtual image lies at d_f = image_distance_mm from the pupil, magnified M:
//   v = d_f - b,  f = v / (M - 1)  (mirror equation with M = v/u),  u = v / M.
// For a field direction, rays from a grid over the (gaze-rotated) eye pupil aimed at the
// virtual image point (at the best-focus distance along that direction, see the .cpp)
// are traced backwards: exact sphere intersection,
// reflection, then the flat display plane. Their spread there (field curvature,
// astigmatism, coma, spherical) becomes an angular RMS blur sigma through the local plate
// scale (chief rays at neighbouring fields). MTF(nu) = MTF_diffraction(nu; pupil, 550 nm)
// * exp(-2 pi^2 sigma^2 nu^2) (Gaussian blur); the MTF30 frequency solves MTF = 0.3.

#include <array>
#include <optional>

#include <Eigen/Core>

#include "model/scene/scene.h"

namespace fovea {

struct CombinerPrescription {
  double mirror_distance_mm = 0;   // b
  double focal_length_mm = 0;      // f = R/2
  double display_distance_mm = 0;  // u, display plane in front of the mirror
};

CombinerPrescription combinerPrescription(const Scene& scene);

// Full field of view of the foveal display's virtual image (horizontal, vertical) in degrees:
// 2 atan(M w / (2 d_f)) per axis, micro-OLED size w, magnification M, image distance d_f
// (seed A.4). The foveated renderer, the 3D view's combiner aperture and the reports use it.
std::array<double, 2> fovealFovDeg(const Scene& scene);

// One backward ray of the unfolded combiner: from point `p` (the frame above: zero-gaze pupil
// at the origin, +z along bench +z) aimed at `q`, reflected by the spherical mirror, to the
// display plane z = b - u. Returns the (x, y) hit in mm, or nullopt when it misses the mirror
// or never reaches the plane. Used by the virtual bench camera (devices/virtual).
std::optional<Eigen::Vector2d> traceCombinerToDisplay(const CombinerPrescription& c, const Eigen::Vector3d& p,
                                                      const Eigen::Vector3d& q);

struct FovealOpticsSample {
  double rms_blur_arcmin = 0;  // 1-D (horizontal) angular RMS blur from aberrations
  double mtf30_cpd = 0;        // with diffraction of the eye pupil
  double best_focus_mm = 0;    // image distance the eye accommodates to (best focus)
};

// field_deg: visual angle (horizontal) relative to bench +z seen from the rotated pupil,
// i.e. gaze + eccentricity.
FovealOpticsSample tracedCombinerMtf30(const Scene& scene, double gaze_yaw_deg, double field_deg);

// Diffraction-limited MTF30 of a circular pupil (cycles per degree).
double diffractionMtf30Cpd(double pupil_diameter_mm, double wavelength_nm);

}  // namespace fovea

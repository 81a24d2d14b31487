#pragma once
// Beam-shaping lens for the peripheral projector (supplement A.2).
//
// Pixel beam: an embedded Gaussian (M^2) beam per scanned pixel. The scene's pixel-beam
// model gives the waist FWHM W at throw z_w and the far-field FWHM growth rate theta
// (full angle). For a Gaussian, FWHM = 1.1774 w (w: 1/e^2 radius), so
//   w0 = W / 1.1774,  theta_half = theta / 1.1774,  z_R = w0 / theta_half = W / theta,
// and the beam propagates as q(z) = (z - z_w) + i z_R with an effective wavelength
// lambda_eff = pi w0 theta_half (= M^2 lambda): w(z)^2 = w0^2 (1 + ((z - z_w)/z_R)^2).
// This matches the waist and the linear growth after it (Fig. S3). Not modelled: the
// larger, elliptical spot right at the exit (scan smear of the resonant MEMS, A.2.1) —
// a single M^2 beam cannot also have it; it only affects the first few cm of throw.
//
// Lens (default): the real stock lens — spherical/plane surfaces with the catalogue's
// thickness, radii from the focal length (plano-convex: R = (n-1) f, curved side to the
// projector; symmetric bi-convex: thick-lens formula), exact chief-ray refraction, and the
// beam propagated through the local 4x4 ray-transfer matrix of that real path (see
// tracePixelReal). Simpler alternative (SpotOptions::thin_lens):
// ideal thin lens at the lens' centre plane, with the chromatic focal length
// f(lambda) = f_d (n_d - 1)/(n(lambda) - 1) (N-BK7 Sellmeier). Chief rays bend by the
// paraxial slope rule s' = s - h/f relative to the lens normal; the Gaussian beam sees
// Coddington's oblique thin-lens powers (Young's astigmatism formulae):
//   P_sagittal = P Phi,  P_tangential = P Phi / cos^2(theta),
//   Phi = (n cos theta' - cos theta) / (n - 1),  sin theta = n sin theta'
// (theta: incidence on the tilted lens). This is what lets a Scheimpflug tilt flatten
// the focal surface onto the oblique HOE. Chief rays outside 90 % of the lens diameter
// miss it and stay unshaped.
//
// Spot: the beam's elliptical 1/e^2 cross-section (tangential/sagittal) projected along
// the ray onto the HOE plane; the per-pixel RMS radius is sqrt(trace) of the footprint's
// intensity covariance (sigma = w/2 along each axis). The figure of merit is the RMS
// over a grid of pixels landing on the HOE and over the projector wavelengths.

#include <array>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "model/analysis/lens_catalog.h"
#include "model/analysis/study_runner.h"
#include "model/scene/scene.h"

namespace fovea {

// Lens placement relative to the projector: distance along its axis, decentre along its
// local x (the scan plane in which the HOE is oblique), tilt about its local y.
struct LensPlacement {
  double distance_mm = 20.0;
  double decenter_mm = 0.0;
  double tilt_deg = 0.0;
};

struct PlacedLens {
  StockLens lens;
  LensPlacement placement;
};

struct SpotOptions {
  int grid_horizontal = 9;  // pixel grid sampled over the projector field
  int grid_vertical = 5;
  // false (default): real thick lens (exact surfaces; beam through the local 4x4 ray-
  // transfer matrix of the real chief ray). true: ideal thin lens with Coddington powers.
  bool thin_lens = false;
};

struct SpotReport {
  double rms_spot_um = 0;       // RMS over pixels on the HOE and wavelengths
  int pixels_on_hoe = 0;        // sampled (pixel, wavelength) pairs landing on the HOE
  int pixels_through_lens = 0;  // of those, how many passed through the lens
  double uncovered_mm = 0;      // how far HOE edge points lie outside the projected field
};

SpotReport evaluateSpots(const Scene& scene, const std::optional<PlacedLens>& lens, const SpotOptions& options = {});

// Radius R of both surfaces (R1 = R, R2 = -R) of a symmetric bi-convex lens of focal length f,
// index n and centre thickness t: the thick-lens equation 1/f = (n-1)(2/R - (n-1) t/(n R^2)),
// its larger root R = (n-1) f (1 + sqrt(1 - t/(n f))), which tends to the thin lens' 2 (n-1) f
// as t -> 0 (Hecht, "Optics", 5th ed., Eq. 6.2). The spot model and the 3D view both use it.
double biconvexRadiusMm(double focal_length_mm, double index, double center_thickness_mm);

// The lens pose in the bench frame for a placement (position, yaw/pitch/roll degrees).
Pose lensPose(const Scene& scene, const LensPlacement& placement);

struct LensCandidateResult {
  StockLens lens;
  LensPlacement placement;
  double rms_spot_um = 0;
  double objective = 0;  // rms + coverage penalty: what the optimiser minimised
  int evaluations = 0;
};

struct LensOptimization {
  PlacedLens best;
  Pose pose;                 // bench pose of the best lens
  double rms_before_um = 0;  // unshaped beam
  double rms_after_um = 0;
  double improvement_percent = 0;               // 100 (before - after) / before
  double distance_bound_mm = 0;                 // farthest lens distance the search allowed (first lens)
  std::vector<LensCandidateResult> candidates;  // best placement per catalogue lens
};

struct LensOptimizationOptions {
  SpotOptions spots;
  int starts_per_lens = 5;    // local BOBYQA runs from spread starting points
  int max_evaluations = 300;  // per start
  // Farthest lens distance from the projector along its axis (mm); default: 15 mm short of
  // the shortest chief-ray throw to the HOE. A form-factor limit ("a lens in front of the
  // projector", A.2.1) is a smaller value.
  std::optional<double> max_distance_mm;
};

// Minimises the RMS spot over catalogue lens, distance, decentre and tilt: NLopt BOBYQA
// (derivative-free, bound-constrained) from several starts per lens, all (lens, start)
// pairs in parallel. Deterministic; Cancelled returns no result.
StudyOutcome<LensOptimization> optimizeBeamShapingLens(const Scene& scene, const std::vector<StockLens>& catalog,
                                                       const LensOptimizationOptions& options = {},
                                                       const StudyControl& control = {});

}  // namespace fovea

#pragma once
// Angular resolution vs eccentricity (supplement A.5), derived from the scene geometry.
//
// Units: resolution in cycles per degree (cpd). A display resolves at most one cycle per
// two pixels (Nyquist), so c = (1/2) dN/d(eps) with N counted in pixels and eps in degrees.
// Integrating 2 c over eccentricity therefore gives back a pixel count (this is the check
// of the seed's Eqs. S6/S13, whose constants K are fixed by "integral = N pixels").
//
// Peripheral display (A.5.2): the scanner puts a constant number of pixels per degree of
// projection angle phi (S7: k_p = N_px / FOV_h). For a gaze (yaw alpha, pitch beta) the
// line of sight at eccentricity eps leaves the pupil centre in direction yaw alpha+eps,
// pitch beta (S10, with the real pupil position on the rotated eye), meets the HOE plane
// at X (S8 with the real, oblique HOE), and X is seen from the projector at horizontal
// projection angle phi(X). dN/deps = k_p |dphi/deps|, by central differences of the exact
// geometry (S9 * S11 in the seed's 1-D paraxial form).
//
// Foveal display (A.5.1): the micro-OLED image is a virtual plane at image_distance d_f
// in front of the pupil (zero gaze), perpendicular to bench z, magnified M, recentred on
// the gaze by the display stage. Its pixels are uniform in the image plane (S2:
// k_f = N_dx / (M w_d)). Departure from S1/S3: the seed writes b (combiner distance) where
// the image plane distance belongs; the line of sight from the rotated pupil
// E = C + r(sin a, cos a) at yaw a+eps meets the image plane z = d_f at
//   x = r sin a + (d_f + r - r cos a) tan(a + eps),
// so centring needs x_f = (d_f + r) tan(a) / M (exact: r sin a - r cos a tan a = 0), and
//   dN/deps = k_f (d_f + r - r cos a) sec^2(a + eps)   (per radian).
//
// Optical limit of the foveal combiner: ray traced through the on-axis magnifier model of
// foveal_optics.h (MTF30 with the eye pupil's diffraction). The scene's parametric model,
// mtf30(theta) = mtf30_on_axis * (1 - field_curvature_per_deg2 * theta^2) with theta the
// field angle at the on-axis combiner (Fig. S7 trend), is reported beside it.
// Perceived: min(display, optical limit, eye limit 60 cpd) where the foveal inset is shown
// (|eps| <= foveation.blend_end_deg and inside the micro-OLED field), otherwise
// min(peripheral, 60 cpd).

#include <array>
#include <optional>
#include <vector>

#include "model/analysis/foveal_optics.h"
#include "model/scene/scene.h"

namespace fovea {

inline constexpr double kEyeLimitCpd = 60.0;  // foveal cone spacing limit (~0.5 arcmin/cycle)

struct ResolutionOptions {
  std::optional<std::array<double, 2>> gaze_deg;  // default: scene.eye.gaze_deg
  std::array<double, 2> hoe_shift_mm{0.0, 0.0};   // HOE lateral shift (HOE local x, y)
  int samples = 241;                              // eccentricity samples over the peripheral field
};

struct ResolutionSample {
  double eccentricity_deg = 0;
  std::optional<double> foveal_cpd;               // empty outside the micro-OLED's field
  std::optional<double> peripheral_cpd;           // empty where the line of sight misses the HOE / projection
  std::optional<double> optical_limit_cpd;        // foveal combiner MTF30 (ray traced), empty outside the foveal field
  std::optional<double> optical_limit_model_cpd;  // the scene's parametric MTF30 model
  std::optional<double> optical_blur_arcmin;      // traced RMS angular blur
  double perceived_cpd = 0;
  bool foveal_shown = false;  // the foveal inset is what the eye sees here
};

struct ResolutionResult {
  int pixels_horizontal = 0;  // projector horizontal pixel count N_px
  double gaze_yaw_deg = 0, gaze_pitch_deg = 0;
  std::array<double, 2> peripheral_field_deg{0, 0};  // eccentricity range on the HOE and in the projection
  std::array<double, 2> foveal_field_deg{0, 0};      // eccentricity range of the micro-OLED image
  double peripheral_pixel_integral = 0;              // integral of 2 c_p over the peripheral field (pixels)
  double peripheral_pixels_on_hoe = 0;               // k_p * |phi(end) - phi(start)|: pixels landing there
  double foveal_pixel_integral = 0;                  // integral of 2 c_f over the foveal field (pixels)
  double projector_pixels_per_deg = 0;               // k_p
  double foveal_image_shift_mm = 0;                  // M x_f: image-plane recentring for the gaze
  std::vector<ResolutionSample> samples;
};

ResolutionResult analyzeResolution(const Scene& scene, const ResolutionOptions& options = {});

// Geometry helpers (exposed for tests): the horizontal projection angle (deg) at which
// the projector sees the HOE point met by the line of sight at eccentricity eps, or empty
// when that line misses the HOE plane, the HOE, or the projection cone.
std::optional<double> projectionAngleForEccentricity(const Scene& scene, double yaw_deg, double pitch_deg,
                                                     double eccentricity_deg, const std::array<double, 2>& hoe_shift_mm,
                                                     bool require_on_hoe = true);

}  // namespace fovea

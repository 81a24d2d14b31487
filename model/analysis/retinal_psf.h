#pragma once
// Retinal point-spread functions of the two displays (issue 29), at the line of sight.
//
// Peripheral (laser projector via the HOE, Maxwellian view): one pixel is the scene's pixel
// beam, the embedded Gaussian of beam_shaping.h: w0 = W/1.1774, theta = div/1.1774 (half
// angle, 1/e^2), z_R = w0/theta, lambda_eff = pi w0 theta (= M^2 lambda; clamped to >= lambda,
// a beam cannot beat diffraction), q(throw) = (throw - z_w) + i z_R in air. The HOE is, on the
// chief ray, a thin lens whose power is that of its recorded hologram: it turns the wave
// diverging from the reference point (distance L_r) into one converging to the signal point
// (L_s), so Phi_rec = 1/L_r + 1/L_s, and at another wavelength the same fringes bend by
// lambda/lambda_rec: Phi = Phi_rec lambda/lambda_rec (per layer: the layer recorded nearest
// the laser). An enabled beam-shaping lens acts as an ideal thin lens on the chief ray
// before the plate. The hologram's obliquity is kept (hologram_astigmatism.h): off its axis the
// HOE has different tangential and sagittal powers (the holographic Coddington equations), and
// it stretches the beam's footprint by cos theta_out / cos theta_in in the plane of incidence,
// so the outgoing beam is astigmatic: a 2x2 complex curvature matrix, propagated through free
// space and the eye as Q -> (A Q + B)(C Q + D)^-1. The plate's finite thickness is neglected;
// then free space to the entrance pupil (on the trace's pupil disc) and the schematic eye
// (schematic_eye.h) to the retina: its paraxial matrix plus, off the line of sight, its oblique
// astigmatism and field curvature at the ray's angle (eye_oblique_focus.h: the Coddington
// pencil of the Navarro eye's conic surfaces onto its curved retina) as a thin astigmatic lens at
// the entrance pupil. The spot on the retina is an elliptical
// Gaussian (1/e^2 radii w_major, w_minor); as a visual angle w_r / B (B = retina mm per radian
// of the chief ray). Its reported size is that of the circle of equal area, w = sqrt(w_major
// w_minor): FWHM = 1.1774 w is the equal-area diameter of the half-maximum ellipse, which holds
// exactly half the power (a 2-D Gaussian holds 1 - f inside its contour at f of the peak), and
// MTF(f) = exp(-2 pi^2 sigma^2 f^2), sigma = w/2, i.e. f_m = sqrt(-ln m / 2) / (pi sigma), the
// MTF along the geometric-mean direction (metrics_major: along the long axis, the worst).
//
// Foveal (micro-OLED via the combiner): the virtual image at d_f in front of the pupil sends
// vergence -1/d_f; the eye's defocus is E = -1/d_f - V_focus(lambda) (schematic_eye.h,
// defocusD). Fourier optics: pupil function P(r) exp(i k E r^2/2) on a disc of the pupil
// diameter, |FFT|^2 = PSF (Goodman, "Introduction to Fourier Optics", ch. 6). The total
// foveal OTF multiplies the eye's OTF by the pixel aperture (a box of the angular pitch:
// sinc(p f)) and the combiner's traced aberration blur (Gaussian of its RMS, foveal_optics.h).

#include <array>
#include <optional>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "model/scene/scene.h"

namespace fovea {

struct SpotMetrics {
  double fwhm_arcmin = 0;  // Gaussian: the FWHM; a pupil PSF: the EE50 diameter (spotWidthArcmin)
  double mtf50_cpd = 0;
  double mtf10_cpd = 0;
};

// FWHM and MTF50/10 of a circular Gaussian spot of 1/e^2 radius w (arcmin).
SpotMetrics gaussianSpotMetrics(double radius_1e2_arcmin);

struct PeripheralSpot {
  bool valid = false;  // the line of sight meets the plate
  double wavelength_nm = 0;
  int layer = -1;              // HOE layer used (recorded nearest the wavelength)
  double throw_mm = 0;         // projector source to the plate point
  double hoe_to_pupil_mm = 0;  // plate point to the pupil centre
  double hoe_power_d = 0;      // Phi of the hologram lens (diopters)
  double lambda_eff_nm = 0;    // M^2 lambda
  double beam_radius_hoe_mm = 0, beam_radius_pupil_mm = 0, beam_radius_retina_mm = 0;  // 1/e^2
  double pupil_transmission = 1;  // Gaussian power inside the pupil disc
  bool through_lens = false;      // the scene's beam-shaping lens (thin-lens model) shaped it
  double radius_1e2_arcmin = 0;   // retinal spot as visual angle (equal-area: sqrt(major x minor))
  SpotMetrics metrics;
  // Additions (the HOE's astigmatism, field dependence):
  std::array<double, 2> field_deg{0, 0};   // the ray's visual angle (yaw, pitch) from the gaze
  std::array<double, 2> vergence_d{0, 0};  // principal vergences right after the plate (D, < 0 converging)
  double astigmatism_d = 0;                // their difference
  double radius_major_arcmin = 0, radius_minor_arcmin = 0;  // 1/e^2 radii of the elliptical spot
  double orientation_deg = 0;                               // long axis from +yaw towards +pitch
  std::array<double, 3> covariance_arcmin2{0, 0, 0};        // yaw-yaw, pitch-pitch, yaw-pitch (sigma^2)
  SpotMetrics metrics_major;                                // along the long axis
  // The eye off its axis (eye_oblique_focus.h): the ray's angle from the line of sight and the
  // extra tangential and sagittal powers of the real eye there (D; 0 on the line of sight).
  double eye_field_deg = 0;
  std::array<double, 2> eye_power_d{0, 0};      // the eye's extra power: meridional, sagittal (D)
  double eye_power_cross_d = 0;                 // and their cross term (a decentred beam's skew part)
  std::array<double, 2> pupil_offset_mm{0, 0};  // where the beam enters: meridional, sagittal from the pupil centre
};

// The peripheral pixel on the line of sight for a gaze, HOE shift (HOE local x, y) and accommodation.
PeripheralSpot peripheralSpot(const Scene& scene, double wavelength_nm, double accommodation_d,
                              std::array<double, 2> gaze_deg, std::array<double, 2> hoe_shift_mm = {0, 0});

// The pixel beam of the projector ray meeting the (shifted) plate at bench point `hit`: the
// field-dependent spot (the HOE's power and astigmatism where that ray meets it).
PeripheralSpot peripheralSpotAt(const Scene& scene, double wavelength_nm, double accommodation_d,
                                std::array<double, 2> gaze_deg, std::array<double, 2> hoe_shift_mm,
                                const Eigen::Vector3d& hit);

// The pupil PSF on a square grid, centred at (n/2, n/2), sum 1.
struct PupilPsf {
  cv::Mat psf;               // CV_64FC1
  double sample_arcmin = 0;  // angular pixel
  double pupil_diameter_mm = 0, wavelength_nm = 0, defocus_d = 0;
};
// grid: FFT size (power of two); the pupil is sampled finely enough for the defocus phase
// and the field wide enough for the geometric blur (see the .cpp).
PupilPsf defocusedPupilPsf(double pupil_diameter_mm, double wavelength_nm, double defocus_d, int grid = 1024);

// Widths measured on a PSF grid (arcmin): FWHM of the profile through the centre along x
// (linear interpolation), the radius enclosing `fraction` of the power, and the first minimum
// of the azimuthally averaged profile (for the Airy pattern).
double psfFwhmArcmin(const cv::Mat& psf, double sample_arcmin);
double encircledEnergyRadiusArcmin(const cv::Mat& psf, double sample_arcmin, double fraction);
double firstMinimumArcmin(const cv::Mat& psf, double sample_arcmin);
// The spot width the JSON reports as spot_fwhm_arcmin: the diameter enclosing half the power
// (EE50). It equals the FWHM exactly for a Gaussian (r50 = w sqrt(ln 2 / 2) = FWHM/2), is 4 %
// above it for the Airy disc (1.070 vs 1.029 lambda/D: 1 - J0^2(x) - J1^2(x) = 1/2 at x = 1.680),
// and stays meaningful for a defocused PSF, whose profile has a bright central spot and rings
// (EE50 diameter of the geometric disc: its diameter / sqrt 2).
double spotWidthArcmin(const cv::Mat& psf, double sample_arcmin);

// MTF along the horizontal frequency axis of a PSF grid times optional extra factors
// (pixel box of angular width pixel_deg, Gaussian RMS blur sigma_arcmin). Frequencies in cpd.
struct MtfCurve {
  std::vector<double> cpd, mtf;
  double frequencyAt(double level) const;  // first crossing (linear interpolation); 0 if none
};
MtfCurve mtfFromPsf(const cv::Mat& psf, double sample_arcmin, double pixel_deg = 0, double sigma_arcmin = 0);

struct FovealSpot {
  double wavelength_nm = 0;
  double defocus_d = 0;                                         // E at the pupil
  double geometric_blur_arcmin = 0;                             // pupil x |E| (angular diameter of the defocus disc)
  double pixel_arcmin = 0;                                      // micro-OLED pixel pitch as visual angle
  double combiner_rms_arcmin = 0;                               // traced combiner aberration blur (foveal_optics.h)
  SpotMetrics eye_only;                                         // the eye's PSF of a point
  SpotMetrics metrics;                                          // eye x pixel x combiner (fwhm_arcmin: spotWidthArcmin)
  double profile_fwhm_arcmin = 0, eye_profile_fwhm_arcmin = 0;  // half-maximum width of the profile
  cv::Mat psf;                                                  // total PSF (CV_64F, sum 1) on its grid
  double sample_arcmin = 0;
};
FovealSpot fovealSpot(const Scene& scene, double wavelength_nm, double accommodation_d, std::array<double, 2> gaze_deg,
                      std::optional<double> pupil_diameter_mm = std::nullopt);

}  // namespace fovea

#pragma once
// Angular and spectral selectivity of each recorded HOE layer at one plate point: the
// diffraction efficiency of the layer alone (no stacking) as the projector's probe is tilted
// away from its nominal direction in the plane of incidence, and as its wavelength is swept.
// This is the "efficiency vs detuning" view of a volume hologram (Kogelnik, Bell Syst. Tech.
// J. 48, 2909, Figs. 5-7): the Bragg peak, its width, and how processing (shrinkage, mean
// index change) or a misplaced projector moves the peak away from the nominal probe.
//
// Geometry (HOE local frame, hoe_recording.h): the grating is recorded at plate point (u, v)
// with the plate at its nominal pose. The nominal probe travels from the projector's point
// source to that point. An angular detuning delta rotates the probe about n x d (n: the film
// normal on the probe's side, d: the probe), so delta > 0 increases the incidence angle
// measured from the normal in the outside medium. Spectral samples keep the nominal
// direction. The probe wavelength of a layer is the projector wavelength closest to the
// layer's recording wavelength (the one it is meant to diffract).

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "model/physics/grating.h"
#include "model/scene/scene.h"

namespace fovea {

struct SelectivityOptions {
  std::array<double, 2> point_mm{0.0, 0.0};  // plate point (HOE local u, v), nominal plate pose
  double angle_span_deg = 10.0;              // detuning range: -span .. +span
  int angle_samples = 401;
  double wavelength_span_nm = 40.0;  // probe wavelength -span .. +span around the layer's
  int wavelength_samples = 401;
  Polarization polarization = Polarization::Unpolarized;
};

struct SelectivitySample {
  double x = 0;  // detuning (deg) or wavelength (nm)
  double efficiency = 0;
  double xi = 0, nu = 0;  // Kogelnik dephasing (signed like vartheta) and coupling (layer alone)
  bool entered = false;   // the probe enters the film (false: grazing/TIR on entry)
};

struct LayerSelectivity {
  std::string name;
  double recording_wavelength_nm = 0;
  double probe_wavelength_nm = 0;
  double incidence_deg = 0;  // nominal probe angle from the film normal, outside medium
  double nominal_efficiency = 0;
  double nominal_xi = 0;
  double peak_detuning_deg = 0, peak_angle_efficiency = 0;
  std::optional<double> angular_fwhm_deg;  // empty when the curve does not fall to half inside the span
  double peak_wavelength_nm = 0, peak_spectral_efficiency = 0;
  std::optional<double> spectral_fwhm_nm;
  std::vector<SelectivitySample> angle, spectrum;
  bool valid = false;  // the grating could be recorded at this point
};

struct SelectivityResult {
  std::array<double, 2> point_mm{0.0, 0.0};
  std::vector<LayerSelectivity> layers;
};

SelectivityResult analyzeSelectivity(const Scene& scene, const SelectivityOptions& options = {});

// Full width at half maximum of a sampled curve around its highest sample, with linear
// interpolation of the half-maximum crossings; empty if a side never falls below half.
std::optional<double> fullWidthHalfMax(const std::vector<SelectivitySample>& curve);

}  // namespace fovea

#pragma once
// Resolution against accommodation (issue 29, seed C.3): the retinal spot and cpd (MTF50,
// MTF10) of the peripheral and the foveal display at the line of sight, for the eye focused
// at each accommodation (0.4..3.3 D: 250..30 cm in the seed). Each sample is the retinal PSF
// model of retinal_psf.h: the peripheral pixel beam through the HOE and the accommodating
// schematic eye (Gaussian; its cpd follows gaussianSpotMetrics), the foveal micro-OLED pixel
// through the defocused pupil (Fourier optics) times the pixel box and the combiner blur.
// The "reference" entries are the laser and the primary nearest 555 nm (as retina-image).

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "model/analysis/retinal_psf.h"
#include "model/scene/scene.h"

namespace fovea {

// The accommodation range the sweep accepts (diopters), that of the schematic eye as the
// retina-image command takes it.
inline constexpr double kAccommodationMinD = 0.0, kAccommodationMaxD = 4.0;
inline constexpr std::size_t kMaxAccommodationSamples = 200;

// "0.4,1,3.3" -> {0.4, 1, 3.3}: finite numbers within kAccommodationMin/MaxD, at most
// kMaxAccommodationSamples of them. Returns the problem ("'x' is not a number") on failure.
struct AccommodationList {
  std::vector<double> values_d;
  std::optional<std::string> problem;
};
AccommodationList parseAccommodationList(const std::string& text);

struct AccommodationSample {
  double accommodation_d = 0;
  std::vector<PeripheralSpot> peripheral;  // per laser
  std::vector<FovealSpot> foveal;          // per micro-OLED primary (psf grids dropped)
};

struct AccommodationResolution {
  std::array<double, 2> gaze_deg{0, 0};
  std::size_t peripheral_reference = 0, foveal_reference = 0;  // entries nearest 555 nm
  std::vector<AccommodationSample> samples;
  // (max - min) / min of the reference peripheral spot over the samples (the seed's
  // "all-in-focus" claim: C.3), null without two valid samples.
  std::optional<double> peripheral_spot_change;
  std::optional<double> foveal_spot_change;
};

AccommodationResolution resolutionVsAccommodation(const Scene& scene, std::array<double, 2> gaze_deg,
                                                  const std::vector<double>& accommodations_d);

}  // namespace fovea

#pragma once
// Per-layer lateral colour of the peripheral display (issue 29).
//
// A projector pixel sends every laser along one direction to one plate point; each laser is
// diffracted by its own layer (recorded at its own wavelength), so the colours of one pixel
// can leave the plate in different directions and reach the eye at different visual angles.
// The grating equation (tangential wave vectors conserved, seed A.1; Kogelnik's K = -K_rec)
// gives, in air on both sides, for a probe along unit a at a plate point whose layer was
// recorded at lambda_rec with reference and signal directions r and s (unit vectors of the
// recording beams at that point):
//     out_t = a_t + (lambda / lambda_rec) (s_t - r_t)                       (t: plate plane)
// With the projector at the reference point (a = r) a laser at its layer's recording
// wavelength leaves along s (to the signal point: no lateral colour); at another wavelength,
// mu = lambda / lambda_rec, out_t = (1 - mu) r_t + mu s_t. The lateral colour of a pixel is the
// difference between its laser's visual angle and the calibration wavelength's (the geometric
// calibration, B.2.1, is one mapping per projector pixel, measured on one colour here: the
// laser nearest 555 nm), so it vanishes where all layers agree.
//
// lateralColourAtLineOfSight traces (RayProbe, the trace's own model) the projector pixel
// whose ray meets the plate where the line of sight does, at every laser, and returns each
// laser's visual angle and its offset from the reference laser's.

#include <array>
#include <vector>

#include "model/scene/scene.h"

namespace fovea {

struct LateralColour {
  double wavelength_nm = 0;
  bool valid = false;                         // the ray enters the pupil (and the reference's does)
  std::array<double, 2> field_deg{0, 0};      // its visual angle (yaw, pitch) from the gaze
  std::array<double, 2> offset_arcmin{0, 0};  // field_deg minus the reference laser's, arcmin
};

// Index of the laser nearest 555 nm (the calibration's colour); 0 when there is none.
std::size_t calibrationLaser(const std::vector<double>& wavelengths_nm);

std::vector<LateralColour> lateralColourAtLineOfSight(const Scene& scene, std::array<double, 2> gaze_deg,
                                                      std::array<double, 2> hoe_shift_mm = {0, 0});

}  // namespace fovea

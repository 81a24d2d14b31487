#pragma once
// The foveal focus stage (issue 30, seed C.3): moving the micro-OLED along the combiner's axis
// moves the virtual image plane of the foveal inset between 30 and 250 cm.
//
// The combiner is the unfolded on-axis magnifier of model/analysis/foveal_optics.h: a concave
// mirror of focal length f = v0 / (M - 1) at b = eye_distance_mm in front of the zero-gaze
// pupil, the panel u0 = v0 / M in front of it, its virtual image v0 = d_f - b behind it
// (the scene's nominal d_f, M). The mirror's focal length is fixed; moving the panel changes
// u, hence v and the image distance d = b + v from the pupil:
//   1/u - 1/v = 1/f  (real object inside f, virtual image; distances positive)
//   v(u) = u f / (f - u),           u(v) = v f / (v + f).
// (The seed's Eq. S1 family writes the magnifier as 1/u + 1/v = 1/f with v signed; with both
// distances positive the virtual image takes the minus sign, as derived here.)
// Vergence of the image at the pupil D = 1000 / d (dioptres, d in mm); the stage's
// sensitivity dD/du = -(1000 / d^2) f^2 / (f - u)^2 (per mm of panel travel), and one encoder
// count of the stage is 1 / counts_per_mm of that.
//
// The check against real rays: focusImageDistanceTraced traces rays backwards from a pupil
// zone through the exact sphere (traceCombinerToDisplay) and finds the image distance whose
// rays meet the axis on the panel plane.
#include "model/analysis/foveal_optics.h"
#include "model/scene/scene.h"

namespace fovea {

struct FocusStageModel {
  double mirror_distance_mm = 0;  // b
  double focal_length_mm = 0;     // f
  double nominal_panel_mm = 0;    // u0: the scene's panel distance (image at d_f)
};

FocusStageModel focusStageModel(const Scene& scene);
// Panel distance u (mm in front of the mirror) -> virtual image distance from the pupil (mm);
// +infinity at u >= f (the image goes to infinity, then real).
double imageDistanceForPanel(const FocusStageModel& m, double panel_mm);
// Image distance from the pupil (mm, > b) -> panel distance u (mm).
double panelForImageDistance(const FocusStageModel& m, double image_mm);
// d(dioptres)/d(panel mm) at a panel distance: negative, the image recedes (D falls) as the
// panel moves away from the mirror towards its focal point.
double dioptresPerMm(const FocusStageModel& m, double panel_mm);

// The focus axis of the bench: the stage binding of element "foveal_display", axis "z" (scene
// format, "stages"), whose element coordinate is the panel's displacement along its own
// optical axis (local +z, the emission direction, towards the combiner) from the scene's
// nominal place: z = u0 - u, so z = 0 puts the image at the scene's d_f, z > 0 brings the
// panel nearer the mirror and the image nearer the eye.
double focusAxisForImageDistance(const FocusStageModel& m, double image_mm);
// The image distance from the pupil (mm) of the focus axis at z (mm); +infinity at u0 - z >= f.
double imageDistanceForFocusAxis(const FocusStageModel& m, double axis_mm);

struct FocusTravel {
  double near_mm = 0, far_mm = 0;                                      // image distances (from the pupil)
  double panel_near_mm = 0, panel_far_mm = 0;                          // u at each
  double travel_mm = 0;                                                // |u_far - u_near|
  double range_d = 0;                                                  // 1000/near - 1000/far
  double sensitivity_near_d_per_mm = 0, sensitivity_far_d_per_mm = 0;  // |dD/du| at each end
};
// Travel needed for the image between near_mm and far_mm (seed C.3: 300 and 2500 mm).
FocusTravel focusTravel(const FocusStageModel& m, double near_mm = 300, double far_mm = 2500);

// Image distance (mm from the pupil) of the panel at `panel_mm` from real rays: rays from the
// pupil zone at radius zone_mm (in the tangential plane) aimed at an axial point at distance d
// are traced back through the sphere to the panel plane; d is solved for the hit at the axis
// (bisection in dioptres). Small zones give the paraxial image, the full pupil adds the
// mirror's spherical aberration.
double focusImageDistanceTraced(const FocusStageModel& m, double panel_mm, double zone_mm);

}  // namespace fovea

#pragma once
// One tolerance trial: a built unit (the nominal scene with the drawn inputs applied) run
// through the bench's gaze sequence with its compensator, reduced to the design's figures
// (tolerance_spec.h, toleranceFigureNames()):
//   fov_min_deg       the smallest FOV along the axis over the spec's gazes
//   fov_zero_gaze_deg the FOV at the gaze nearest zero
//   eyebox_mm         pupil-centre range around zero gaze over which FOV >= FOV(0) -
//                     eyebox_tolerance_deg, its ends interpolated linearly between gaze samples
//   inset_error_deg   where the foveal inset lands on the retina relative to the fovea: the
//                     inset follows the gaze the tracker reports, so the tracker's error
//   mean_efficiency   mean over the gazes of the mean efficiency of the rays in the pupil
// The bench (seed A.3, C.1): the tracker reports gaze + error; the compensator commands the
// shift for the reported gaze (Refind: x_p re-found on this unit by optimiseShift; Fixed:
// the nominal design's x_p table, interpolated); the stage ends at the commanded position plus
// its repeatability offset, short by half its backlash on the side it came from (the gazes are
// visited in increasing order from the home position 0); the eye looks at the true gaze.

#include <vector>

#include "model/analysis/gaze_studies.h"
#include "model/analysis/tolerance_spec.h"

namespace fovea {

// The nominal design's x_p(gaze) at the spec's gazes (the Fixed compensator's table).
struct CompensationTable {
  std::vector<double> gazes_deg, shifts_mm;
  double at(double gaze_deg) const;  // linear interpolation, clamped at the ends
};
CompensationTable nominalCompensation(const Scene& scene, const ToleranceSpec& spec, const FovEvaluator& eval);

// The scene of a unit: scene paths offset, laser wavelengths drifted. Throws
// std::invalid_argument if a perturbed value breaks the scene rules.
Scene perturbedScene(const Scene& scene, const ToleranceSpec& spec, const std::vector<double>& inputs);

// The figures of one unit, in toleranceFigureNames() order.
std::vector<double> runToleranceTrial(const Scene& scene, const ToleranceSpec& spec, const FovEvaluator& eval,
                                      const std::vector<double>& inputs, const CompensationTable& nominal_table);

// The evaluator the trials use: the edge FOV estimator at the spec's tolerance.
FovEvaluator toleranceEvaluator(const ToleranceSpec& spec);

}  // namespace fovea

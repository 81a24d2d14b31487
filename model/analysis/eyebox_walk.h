#pragma once
// The eye box of finishSweep (gaze_studies.h) with only the x_p searches it reads: the walk out
// from zero gaze stops at the first sweep gaze outside the box on each side and bisects there,
// so the sweep gazes beyond it (most of a -40..40 sweep for a narrow box) are never traced.
// Same gazes, same tests, same bisections as finishSweep on a full sweepGaze: the same EyeBox
// bit for bit, from `sample` (which must return optimiseShift's sample at that gaze; the fit's
// observables pass their memo, so a gaze shared with an x_p target is searched once).

#include <functional>
#include <optional>
#include <utility>
#include <vector>

#include "model/analysis/gaze_studies.h"

namespace fovea {

using GazeSampleSource = std::function<GazeSample(double gaze_deg)>;

// One border of the eye box, on the side of `direction` (-1: negative gazes, +1: positive):
// the side's `gazes` by |gaze| through `at_gaze` (a sweep's computed sample or a lazy search)
// until the first outside the box, then `bisections` halvings between the last inside and it
// through `search` (new gazes). Returns the last sample inside (`reference` if none) and whether
// an outside gaze bounded the side; nullopt when `control` cancelled a bisection.
std::optional<std::pair<GazeSample, bool>> eyeBoxBorder(const std::vector<double>& gazes, int direction,
                                                        const GazeSample& reference,
                                                        const std::function<bool(const GazeSample&)>& inside_box,
                                                        const GazeSampleSource& at_gaze, const GazeSampleSource& search,
                                                        int bisections, const StudyControl& control);

// gazes: the sweep's gazes (sweepGazes()); sample(0.0) is the reference. Both sides run in
// parallel, so `sample` must be thread-safe.
EyeBox walkEyeBox(const std::vector<double>& gazes, GazeAxis axis, const GazeStudyOptions& options,
                  const GazeSampleSource& sample);

}  // namespace fovea

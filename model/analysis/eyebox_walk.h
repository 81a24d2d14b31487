#pragma once
// The eye box of finishSweep (gaze_studies.h) with only the x_p searches it reads: the walk out
// from zero gaze stops at the first sweep gaze outside the box on each side and bisects there,
// so the sweep gazes beyond it (most of a -40..40 sweep for a narrow box) are never traced.
// Same gazes, same tests, same bisections as finishSweep on a full sweepGaze: the same EyeBox
// bit for bit, from `sample` (which must return optimiseShift's sample at that gaze; the fit's
// observables pass their memo, so a gaze shared with an x_p target is searched once).

#include <functional>
#include <vector>

#include "model/analysis/gaze_studies.h"

namespace fovea {

using GazeSampleSource = std::function<GazeSample(double gaze_deg)>;

// gazes: the sweep's gazes (sweepGazes()); sample(0.0) is the reference. Both sides run in
// parallel, so `sample` must be thread-safe.
EyeBox walkEyeBox(const std::vector<double>& gazes, GazeAxis axis, const GazeStudyOptions& options,
                  const GazeSampleSource& sample);

}  // namespace fovea

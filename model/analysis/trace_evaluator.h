#pragma once
// The FOV evaluator of the gaze studies backed by the HOE ray tracer (model/physics/trace.h).
//
// The studies use the *continuous* FOV, not the tracer's extent (max - min of the lit field
// angles): when the Maxwellian focus is blurred or Bragg mismatch darkens parts of the
// plate, scattered rays can still reach the pupil from both ends of the field while most
// pixels in between are dark (the seed's "blind regions", A.3). Per wavelength, along
// every row of the projector grid the widest run of consecutive lit rays (in the pupil,
// efficiency >= threshold) gives a horizontal span, along every column a vertical one;
// the FOV is the widest over rows (columns), and the smallest over the wavelengths (the
// field shown in every colour). Diagonal: the angle between the corners of those spans.

#include <optional>
#include <vector>

#include "model/analysis/gaze_studies.h"
#include "model/physics/trace.h"

namespace fovea {

struct TraceEvaluatorOptions {
  int rays = 12000;                     // rays per wavelength over the projector field
  std::optional<double> wavelength_nm;  // default: all projector wavelengths
  double efficiency_threshold = 0.1;
};

struct ContinuousFov {
  double horizontal_deg = 0, vertical_deg = 0, diagonal_deg = 0;
};
ContinuousFov continuousFov(const std::vector<TracedRay>& rays, double efficiency_threshold);

FovEvaluator traceEvaluator(const TraceEvaluatorOptions& options = {});

}  // namespace fovea

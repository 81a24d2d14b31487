#pragma once
// The FOV evaluator of the gaze studies backed by the HOE ray tracer (model/physics/trace.h).
//
// The studies use the *continuous* FOV, not the tracer's extent (max - min of the lit field
// angles): when the Maxwellian focus is blurred or Bragg mismatch darkens parts of the
// plate, scattered rays can still reach the pupil from both ends of the field while most
// pixels in between are dark (the seed's "blind regions", A.3). Per wavelength, along the
// projector-grid row through the line of sight (that of the lit ray nearest the field
// centre) the widest run of consecutive lit rays (in the pupil, efficiency >= threshold)
// gives the horizontal FOV, along that column the vertical one (the seed's top and side
// views); the smallest over the wavelengths is kept (the field shown in every colour).
// Diagonal: the angle between the corners of those spans.

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
ContinuousFov continuousFov(const std::vector<FieldRay>& rays, double efficiency_threshold);  // the same, leaner

// Always true since the tracer landed (kept for callers written before it).
inline bool traceEvaluatorAvailable() {
  return true;
}

FovEvaluator traceEvaluator(const TraceEvaluatorOptions& options = {});

}  // namespace fovea

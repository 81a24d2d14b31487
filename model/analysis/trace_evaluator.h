#pragma once
// The FOV evaluator of the gaze studies backed by the HOE ray tracer (model/physics/trace.h).

#include <optional>

#include "model/analysis/gaze_studies.h"

namespace fovea {

struct TraceEvaluatorOptions {
  int rays = 1500;                      // rays per wavelength over the projector field
  std::optional<double> wavelength_nm;  // default: all projector wavelengths
  double efficiency_threshold = 0.1;
};

// True when the tracer is part of this build.
bool traceEvaluatorAvailable();

// Throws std::runtime_error when called without the tracer in the build.
FovEvaluator traceEvaluator(const TraceEvaluatorOptions& options = {});

}  // namespace fovea

#pragma once
// Comparing scenes for what a consumer depends on.

#include "model/scene/scene.h"

namespace fovea {

// Whether `a` and `b` differ at most in the eye's gaze: a gaze drag changes nothing else, and
// what depends only on the rest (the diffraction, the virtual bench's camera maps, the
// foveated preview's compositor) need not be recomputed.
inline bool equalButGaze(const Scene& a, const Scene& b) {
  if (a.eye.gaze_deg == b.eye.gaze_deg) return a == b;
  Scene turned = a;
  turned.eye.gaze_deg = b.eye.gaze_deg;
  return turned == b;
}

}  // namespace fovea

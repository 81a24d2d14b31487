#pragma once
// The small tolerance spec the tolerance tests run (fovea-cli tolerance, the studio's Tolerance
// analysis, the report's Tolerance section): cheap trials, with a pass rate strictly between 0
// and 1 (the tracker's +-1.5 deg fails the 1 deg inset bound about a third of the time).
// tests/slurm/tolerance-spec.json is the same spec as a file for the Slurm job.
#include <QByteArray>

namespace fovea::testing {

// HOE x (normal, sigma 0.3 mm), then `more_parameters` (JSON objects, each followed by a
// comma, e.g. eye relief), then the gaze tracker (uniform, +-1.5 deg); the fixed compensator,
// three yaw gazes (-10, 0, 10 deg) at 532 nm; pass: smallest FOV >= 60 deg, inset error
// <= 1 deg; target yield 0.9.
inline QByteArray smallToleranceSpec(const QByteArray& more_parameters = {}) {
  return R"({
  "format": "fovea-tolerance",
  "parameters": [
    {"name": "HOE x", "path": "hoe.position_mm[0]", "distribution": "normal", "sigma": 0.3},
    )" + more_parameters +
         R"(
    {"name": "gaze tracker", "kind": "gaze_tracker", "distribution": "uniform", "half_width": 1.5}
  ],
  "gaze": {"axis": "yaw", "from_deg": -10, "to_deg": 10, "step_deg": 10},
  "compensator": "fixed",
  "wavelength_nm": 532,
  "pass": {"fov_min_deg": {"min": 60}, "inset_error_deg": {"max": 1.0}},
  "target_yield": 0.9,
  "fov_tolerance_deg": 0.05
})";
}

}  // namespace fovea::testing

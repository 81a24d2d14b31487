#include "model/gaze/eye_tracker_calibration.h"

#include <exception>
#include <stdexcept>
#include <string>
#include <thread>

namespace fovea::gaze {

std::uint32_t eyeCameraSeed(std::optional<EyeSide> side, std::uint32_t seed) {
  return side == EyeSide::Left ? seed + 1000003u : seed;
}

TrackedCalibrationOptions eyeTrackerCalibrationOptions(const Scene& scene, std::optional<EyeSide> side,
                                                       PupilDetectorKind detector, std::uint32_t seed) {
  TrackedCalibrationOptions o;
  o.eye.pupil_diameter_mm = side ? eyeScene(scene, *side).eye.pupil_diameter_mm : scene.eye.pupil_diameter_mm;
  o.seed = eyeCameraSeed(side, seed);
  o.detector_kind = detector;
  return o;
}

EyeTrackerCalibrations calibrateEyeTrackers(const Scene& scene, PupilDetectorKind detector, std::uint32_t seed) {
  EyeTrackerCalibrations out;
  const bool both = scene.binocular.has_value();
  out.right_options =
      eyeTrackerCalibrationOptions(scene, both ? std::optional(EyeSide::Right) : std::nullopt, detector, seed);
  if (!both) {
    out.right = calibrateWithTracker(out.right_options);
    return out;
  }
  out.left_options = eyeTrackerCalibrationOptions(scene, EyeSide::Left, detector, seed);
  // Each eye's failure names its eye (a target the tracker lost, a missing learned model).
  std::string left_error, right_error;
  std::thread left([&] {
    try {
      out.left = calibrateWithTracker(*out.left_options);
    } catch (const std::exception& e) {
      left_error = e.what();
    }
  });
  try {
    out.right = calibrateWithTracker(out.right_options);
  } catch (const std::exception& e) {
    right_error = e.what();
  }
  left.join();
  if (!left_error.empty()) throw std::invalid_argument("left eye camera: " + left_error);
  if (!right_error.empty()) throw std::invalid_argument("right eye camera: " + right_error);
  return out;
}

}  // namespace fovea::gaze

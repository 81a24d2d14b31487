#pragma once
// The tracked gaze calibration of a scene's eye trackers (issue 30 item 5): one eye camera
// per eye — the only eye of a monocular scene, both of a binocular one — each with its own
// virtual camera noise (seed) and its own eye (pupil diameter from eyeScene(scene, side)),
// calibrated as model/gaze/tracked_calibration.h does. The capture wizard's gaze session and
// `fovea-cli calibrate gaze` run this; `fovea-cli closed-loop --binocular` calibrates its two
// trackers with the same seeds (eyeCameraSeed), so at the same seed the three agree.
//
// The left eye's camera sits in the mirror image of the right one's place and sees the
// mirror image of its eye (the bench is mirror-symmetric about the mid-plane); in the eye's
// own, mirrored frame the calibration is the right eye's with its own noise.

#include <cstdint>
#include <optional>

#include <nlohmann/json.hpp>

#include "model/gaze/tracked_calibration.h"
#include "model/scene/eye_scene.h"
#include "model/scene/scene.h"

namespace fovea::gaze {

// The seed of an eye camera's noise for a run's seed: the right eye's (and a monocular
// scene's only eye's) is the seed itself, the left eye's the seed + 1000003 (a prime offset:
// the two cameras never share their noise, whatever the run's seed).
std::uint32_t eyeCameraSeed(std::optional<EyeSide> side, std::uint32_t seed);

// The options for the eye of `scene` on `side` (none: a monocular scene's only eye).
// Throws std::invalid_argument for a side of a monocular scene (eyeScene's error).
TrackedCalibrationOptions eyeTrackerCalibrationOptions(const Scene& scene, std::optional<EyeSide> side,
                                                       PupilDetectorKind detector = PupilDetectorKind::Classical,
                                                       std::uint32_t seed = 1);

struct EyeTrackerCalibrations {
  TrackedCalibrationOptions right_options;  // a monocular scene's only eye
  TrackedCalibration right;
  std::optional<TrackedCalibrationOptions> left_options;  // binocular scenes
  std::optional<TrackedCalibration> left;
};

// Calibrates every eye tracker of the scene (a binocular scene's two in parallel: their
// cameras and detectors are independent). Throws as calibrateWithTracker.
EyeTrackerCalibrations calibrateEyeTrackers(const Scene& scene,
                                            PupilDetectorKind detector = PupilDetectorKind::Classical,
                                            std::uint32_t seed = 1);

}  // namespace fovea::gaze

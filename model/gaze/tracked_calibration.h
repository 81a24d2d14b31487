#pragma once
// The gaze calibration of seed C.4 fed by the pupil detector on rendered eye-camera frames:
// five fixation targets (centre and the corners of +-15 x +-10 deg), each the average of its
// last 10 accepted samples, frames whose detection confidence is below min_confidence
// rejected as outliers (blinks, lashes, a glint on the outline); accuracy and precision in
// degrees on a held-out grid of eight targets (the four edge midpoints and four points
// halfway to the corners). Fixational eye movements during a target: Gaussian jitter of
// fixation_jitter_deg per axis (drift and microsaccades are ~0.1 deg, Martinez-Conde et al.
// 2004).

#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "model/gaze/eye_image_renderer.h"
#include "model/gaze/gaze_calibration.h"
#include "model/gaze/pupil_detector.h"
#include "model/gaze/pupil_detector_choice.h"

namespace fovea::gaze {

struct TrackedCalibrationOptions {
  IrCameraPose camera;
  EyeAppearance eye;
  int leds = 6;
  double led_ring_radius_mm = 10;
  int samples_per_target = 10;
  int extra_frames = 4;         // frames captured beyond the samples, to replace rejected ones
  double min_confidence = 0.6;  // outlier rejection
  double fixation_jitter_deg = 0.05;
  PupilDetectorOptions detector;
  PupilDetectorKind detector_kind = PupilDetectorKind::Classical;  // learned/auto: pupil_detector_choice.h
  std::uint32_t seed = 1;
};

struct TrackedCalibration {
  std::vector<GazeTarget> targets;  // accepted pupil centres per target
  GazeCalibrationResult result;
  int frames = 0, rejected = 0;
};

// Throws std::invalid_argument when a target keeps too few accepted samples to fit.
TrackedCalibration calibrateWithTracker(const TrackedCalibrationOptions& options);

// The result as the capture session's manifest keeps it ("gaze_calibration"): method, targets,
// detector, samples_per_target, min_confidence, accuracy_mean_deg / _max_deg, precision_rms_s2s_deg,
// precision_sd_deg, held_out_targets, validation, fit_rms_deg, frames, rejected, seed and the
// per-target errors.
nlohmann::json trackedCalibrationJson(const TrackedCalibration& calibration, const TrackedCalibrationOptions& options);

}  // namespace fovea::gaze

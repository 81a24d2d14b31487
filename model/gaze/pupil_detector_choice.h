#pragma once
// The pupil detector a caller chooses: classical (pupil_detector.h), learned
// (learned_pupil_detector.h) or auto, the learned detector's proposal refined by the
// classical ellipse fit: the classical detector runs on a window around the learned centre
// (2.5 pupil diameters, at least 96 px) and its ellipse is taken when its centre lies within
// the acceptance radius of the learned one (the fit is the more exact outline where it agrees;
// the proposal keeps it from locking on a shadow, lid crease or glint cluster beside the
// pupil); otherwise the learned ellipse stands. No pupil from the learned detector: none from
// auto (closed eyes). docs/gaze-tracking.md has the measurements behind that choice
// (scripts/auto-radius-sweep.py repeats them).

#include <optional>
#include <string>

#include "model/gaze/learned_pupil_detector.h"
#include "model/gaze/pupil_detector.h"

namespace fovea::gaze {

enum class PupilDetectorKind { Classical, Learned, Auto };

const char* detectorName(PupilDetectorKind kind);
std::optional<PupilDetectorKind> parseDetectorKind(const std::string& name);  // classical|learned|auto
inline constexpr const char* kDetectorChoices = "classical, learned, auto";

// Auto's acceptance radius, frame px of a 400 x 400 eye-camera frame (scale it with another
// camera's resolution). 2 px, with no term in the pupil's diameter: chosen on the wide domain's
// held-out subsets at seed 5 (1000 frames each; the benchmark's seeds are 2026 and 99) for the
// stages of 2026-12-06, seventh session (median centre error 0.34-1.52 px). There every radius
// from 1 to 3 px placed as many centres within 5 px as the network alone on every subset, and
// 2 px lowered the median error of easy, glints, off-axis and partial frames (0.14-0.67 px
// against 0.35-0.81 px) and the others' by at most 0.01 px; the former max(2 px, 0.1 diameters),
// chosen for a network three times less precise, let fits up to 18 px from a large pupil's
// proposal through and lost 0.9-2.9 points on every subset (scripts/auto-radius-sweep.py).
inline constexpr double kAutoAcceptRadiusPx = 2.0;

// Runs the chosen detector. The learned model is loaded once per thread from the default
// search (findPupilModel); a missing model throws std::runtime_error naming the paths.
// `refine_scale_above`: the learned detector's scaled refining window (learned_pupil_detector.h).
PupilDetection detectPupilWith(PupilDetectorKind kind, const cv::Mat& image, const PupilDetectorOptions& classical = {},
                               double learned_min_confidence = kLearnedMinConfidence,
                               double auto_accept_radius_px = kAutoAcceptRadiusPx,
                               double refine_scale_above = kRefineScaleAboveMajor);

// Loads the learned model now (throws as above): a command checks it before any work.
void requireLearnedModel();

// The files the learned detector runs (loading it as requireLearnedModel does): the network
// and its refining stage (empty when there is none beside it; learned_pupil_detector.h).
struct LearnedModelFiles {
  std::string model, refine;
};
LearnedModelFiles learnedModelFiles();

}  // namespace fovea::gaze

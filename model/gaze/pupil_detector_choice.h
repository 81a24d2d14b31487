#pragma once
// The pupil detector a caller chooses: classical (pupil_detector.h), learned
// (learned_pupil_detector.h) or auto, the learned detector's proposal refined by the
// classical ellipse fit: the classical detector runs on a window around the learned centre
// (2.5 pupil diameters, at least 96 px) and its ellipse is taken when it lies within
// max(2 px, 0.1 diameters) of the learned centre (the fit is the more exact outline where it
// holds; the proposal keeps it from locking on a shadow or lash elsewhere); otherwise the
// learned ellipse stands. No pupil from the learned detector: none from auto (closed eyes).
// docs/gaze-tracking.md has the measurements behind that choice.

#include <optional>
#include <string>

#include "model/gaze/pupil_detector.h"

namespace fovea::gaze {

enum class PupilDetectorKind { Classical, Learned, Auto };

const char* detectorName(PupilDetectorKind kind);
std::optional<PupilDetectorKind> parseDetectorKind(const std::string& name);  // classical|learned|auto
inline constexpr const char* kDetectorChoices = "classical, learned, auto";

// Runs the chosen detector. The learned model is loaded once per thread from the default
// search (findPupilModel); a missing model throws std::runtime_error naming the paths.
PupilDetection detectPupilWith(PupilDetectorKind kind, const cv::Mat& image, const PupilDetectorOptions& classical = {},
                               double learned_min_confidence = 0.5);

// Loads the learned model now (throws as above): a command checks it before any work.
void requireLearnedModel();

// The files the learned detector runs (loading it as requireLearnedModel does): the network
// and its refining stage (empty when there is none beside it; learned_pupil_detector.h).
struct LearnedModelFiles {
  std::string model, refine;
};
LearnedModelFiles learnedModelFiles();

}  // namespace fovea::gaze

#pragma once
// The learned pupil detector: a small CNN (scripts/train_pupil_net.py, trained on the wide
// synthetic domain of wide_eye_domain.h) run by OpenCV's DNN module from an ONNX file, no
// Python at run time. The frame (any size; CV_8U grey, BGR or float as detectPupil takes)
// is padded to a square, downscaled to 96 x 96 (INTER_AREA, as the training frames were)
// and the network regresses the full pupil ellipse (centre, axes, angle) and whether a
// pupil is visible; its probability is the confidence. The frame and its mirror image run as
// one batch of two and their outputs are averaged (test-time flip augmentation), so this
// stage is mirror-equivariant. It returns the classical detector's
// PupilDetection (no glints: the network does not locate them).
//
// A second, refining stage (pupil-refine.onnx beside the model file, the same network trained
// on windows: scripts/train_pupil_net.py --stage refine) looks again at twice the resolution:
// the frame downscaled to 200 x 200, a 96 x 96 window of it centred on the first stage's
// centre, and the ellipse regressed in the window's units (one pass: the 3 ms budget).
// Without that file the detector is the one stage; refineModelPath() says which it is.
//
// The model file is read at run time, never compiled in (build time, issue 25). Looked for:
// $FOVEA_PUPIL_MODEL when set (then only there); else, in order, the install tree (<exe>/../share/fovea-studio/pupil/
// pupil-net.onnx, then the configured install prefix); the source tree's
// resources/pupil/pupil-net.onnx (build-tree runs).

#include <memory>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "model/gaze/pupil_detector.h"

namespace fovea::gaze {

inline constexpr int kLearnedPupilInputPx = 96;
inline constexpr int kLearnedPupilOutputs = 7;     // centre x, y, axes, cos 2θ, sin 2θ, visibility
inline constexpr int kLearnedPupilCanvasPx = 200;  // the refining stage's downscaled frame
// The visibility sigmoid at or above which the detector reports a pupil.
inline constexpr double kLearnedMinConfidence = 0.5;

// The candidate paths in search order, and the first that exists; findPupilModel throws
// std::runtime_error naming every path tried when none does.
std::vector<std::string> pupilModelCandidates();
std::string findPupilModel();

class LearnedPupilDetector {
 public:
  // Loads the model (the default search when `model_path` is empty). Throws
  // std::runtime_error "pupil model PATH: ..." when the file is missing or unreadable.
  explicit LearnedPupilDetector(const std::string& model_path = {});
  ~LearnedPupilDetector();
  LearnedPupilDetector(LearnedPupilDetector&&) noexcept;
  LearnedPupilDetector& operator=(LearnedPupilDetector&&) noexcept;

  // Not thread-safe (one forward pass at a time); confidence below min_confidence: not found.
  PupilDetection detect(const cv::Mat& image, double min_confidence = kLearnedMinConfidence);
  const std::string& modelPath() const { return path_; }
  // The refining stage's model, empty when there is none beside modelPath().
  const std::string& refineModelPath() const { return refine_path_; }

 private:
  struct Net;
  std::unique_ptr<Net> net_;
  std::string path_, refine_path_;
};

}  // namespace fovea::gaze

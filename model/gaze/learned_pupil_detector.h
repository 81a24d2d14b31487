#pragma once
// The learned pupil detector: a small CNN (scripts/train_pupil_net.py, trained on the wide
// synthetic domain of wide_eye_domain.h) run by OpenCV's DNN module from an ONNX file, no
// Python at run time. The frame (any size; CV_8U grey, BGR or float as detectPupil takes)
// is padded to a square, downscaled to 96 x 96 (INTER_AREA, as the training frames were)
// and the network regresses the full pupil ellipse (centre, axes, angle) and whether a
// pupil is visible; its probability is the confidence. The frame and its mirror image run as
// one batch of two and their outputs are averaged (test-time flip augmentation), so the
// detector is mirror-equivariant. It returns the classical detector's
// PupilDetection (no glints: the network does not locate them).
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
inline constexpr int kLearnedPupilOutputs = 7;  // centre x, y, axes, cos 2θ, sin 2θ, visibility

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
  PupilDetection detect(const cv::Mat& image, double min_confidence = 0.5);
  const std::string& modelPath() const { return path_; }

 private:
  struct Net;
  std::unique_ptr<Net> net_;
  std::string path_;
};

}  // namespace fovea::gaze

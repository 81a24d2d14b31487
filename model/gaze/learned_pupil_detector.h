#pragma once
// The learned pupil detector: a small CNN (scripts/train_pupil_net.py, trained on the wide
// synthetic domain of wide_eye_domain.h) run by OpenCV's DNN module from an ONNX file, no
// Python at run time. The frame (any size; CV_8U grey, BGR or float as detectPupil takes)
// is padded to a square, downscaled to 96 x 96 (INTER_AREA, as the training frames were)
// and the network regresses the full pupil ellipse (centre, axes, angle) and whether a
// pupil is visible; its probability is the confidence. Alone, this stage runs the frame and its
// mirror image as one batch of two and averages their outputs (test-time flip augmentation),
// so it is mirror-equivariant; before a refining stage, only frames whose visibility is near
// the threshold get the mirror's pass. It returns the classical detector's PupilDetection (no
// glints: the network does not locate them).
//
// A second, refining stage (pupil-refine.onnx beside the model file, the same network trained
// on windows: scripts/train_pupil_net.py --stage refine) looks again at twice the resolution:
// the frame downscaled to 200 x 200 (less for a large pupil: kRefineScaleAboveMajor), a 96 x 96
// window of it centred on the first stage's centre, and the ellipse regressed in the window's
// units (one pass: the 3 ms budget).
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
// Before a refining stage the first stage runs the mirror image too only when its visibility
// logit is within this of the threshold's. Chosen at seed 5 (docs/gaze-tracking.md): from a band
// of 3 up, every one of its 8000 frames was found or not as with the flip on every frame (2: two
// frames not); 4 for a margin, about 1 % of the frames. At seeds 2026 and 99, likewise every frame.
inline constexpr double kFirstStageFlipBandLogit = 4;
// The refining window scales with the pupil: a first-stage major axis m above this fraction of
// the window's span at the 200 px canvas (192 px of a 400 px frame; T frame px) shrinks the canvas
// to round(200 T / m) px (at least 96), so the pupil looks T px wide and the window spans the
// frame around it in proportion (192 m / T px). The refining stage was trained so, T drawn from
// 90-150 px per window (scripts/train_pupil_net.py --scale-above); T = 120 px was chosen within
// that range at seed 5 (scripts/refine-scale-sweep.py; docs/gaze-tracking.md), the T that placed
// the most of the hard set's centres within 5 px: 95.5 % (90 / 105 / 135 / 150 px 94.5 / 94.9 /
// 95.2 / 94.9 %, a fixed canvas 94.6 %), the other subsets within 0.4 points. 0: never scale.
inline constexpr double kRefineScaleAboveMajor = 0.625;

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
  // `refine_scale_above`: kRefineScaleAboveMajor's fraction (a sweep's; 0: a fixed 200 px canvas).
  PupilDetection detect(const cv::Mat& image, double min_confidence = kLearnedMinConfidence,
                        double refine_scale_above = kRefineScaleAboveMajor);
  const std::string& modelPath() const { return path_; }
  // The refining stage's model, empty when there is none beside modelPath().
  const std::string& refineModelPath() const { return refine_path_; }

 private:
  struct Net;
  std::unique_ptr<Net> net_;
  std::string path_, refine_path_;
};

}  // namespace fovea::gaze

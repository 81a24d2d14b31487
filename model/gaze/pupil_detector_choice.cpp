#include "model/gaze/pupil_detector_choice.h"

#include <algorithm>
#include <cmath>

#include "model/gaze/learned_pupil_detector.h"

namespace fovea::gaze {
namespace {

// One network per thread (a cv::dnn::Net is not to be shared between threads). A constructor
// that throws (no model file) leaves it uninitialised, and the next call tries again
// ([stmt.dcl]: an initialisation that exits by an exception is retried).
LearnedPupilDetector& threadDetector() {
  thread_local LearnedPupilDetector net;
  return net;
}

PupilDetection refined(const cv::Mat& image, const PupilDetection& learned, const PupilDetectorOptions& o,
                       double accept_radius_px) {
  const cv::Mat grey = toGrey8(image);
  const double diameter = std::max(learned.ellipse.major_px, 1.0);
  const int side = static_cast<int>(std::max(96.0, 2.5 * diameter));
  const cv::Rect window = cv::Rect(cvRound(learned.ellipse.centre.x - side / 2.0),
                                   cvRound(learned.ellipse.centre.y - side / 2.0), side, side) &
                          cv::Rect(0, 0, grey.cols, grey.rows);
  if (window.width < 2 * o.min_diameter_px || window.height < 2 * o.min_diameter_px) return learned;
  PupilDetection c = detectPupil(grey(window), o);
  if (!c.found) return learned;
  const cv::Point2d offset(window.x, window.y);
  c.ellipse.centre += offset;
  for (auto& g : c.glints_px) g += offset;
  const double moved =
      std::hypot(c.ellipse.centre.x - learned.ellipse.centre.x, c.ellipse.centre.y - learned.ellipse.centre.y);
  if (!(moved <= accept_radius_px)) return learned;
  c.confidence = std::max(c.confidence, learned.confidence);
  return c;
}

}  // namespace

const char* detectorName(PupilDetectorKind kind) {
  switch (kind) {
    case PupilDetectorKind::Classical:
      return "classical";
    case PupilDetectorKind::Learned:
      return "learned";
    case PupilDetectorKind::Auto:
      return "auto";
  }
  return "?";
}

std::optional<PupilDetectorKind> parseDetectorKind(const std::string& name) {
  for (PupilDetectorKind k : {PupilDetectorKind::Classical, PupilDetectorKind::Learned, PupilDetectorKind::Auto})
    if (name == detectorName(k)) return k;
  return std::nullopt;
}

void requireLearnedModel() {
  threadDetector();
}

LearnedModelFiles learnedModelFiles() {
  const auto& net = threadDetector();
  return {net.modelPath(), net.refineModelPath()};
}

PupilDetection detectPupilWith(PupilDetectorKind kind, const cv::Mat& image, const PupilDetectorOptions& classical,
                               double learned_min_confidence, double auto_accept_radius_px, double refine_scale_above) {
  if (kind == PupilDetectorKind::Classical) return detectPupil(image, classical);
  PupilDetection learned = threadDetector().detect(image, learned_min_confidence, refine_scale_above);
  if (kind == PupilDetectorKind::Learned || !learned.found) return learned;
  return refined(image, learned, classical, auto_accept_radius_px);
}

}  // namespace fovea::gaze

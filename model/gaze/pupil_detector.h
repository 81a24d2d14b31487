#pragma once
// Classical dark-pupil detector for IR eye-camera frames, after the published detectors:
//  1. proposal: the darkest pupil-sized blob on a 1/4-scale frame, by the centre-surround
//     (Haar-like) response on an integral image (Swirski, Bulling, Dodgson, "Robust
//     real-time pupil tracking in highly off-axis images", ETRA 2012; the Pupil Labs 2-D
//     detector, Kassner et al. 2014);
//  2. in a region of interest around it: a threshold between the pupil's level (median of
//     the proposal's centre) and the surround's (median of the region), corneal glints
//     (saturated specks) filled in and their neighbourhood excluded from the edges, thin
//     eyelashes removed by a morphological opening (ExCuSe, Fuhl et al. 2015);
//  3. edge points: the outline of the dark blob, without the points where the bright side is
//     brighter than the iris can be (an eyelid edge cutting the pupil: ElSe, Fuhl et al.
//     2016, filters edges the same way);
//  4. RANSAC ellipse fit (5-point samples, inliers within 1.5 px, refits on the inliers),
//     constrained to plausible pupils (size, aspect >= 0.4, dark inside);
//  5. confidence (PuRe, Santini, Fuhl, Kasneci 2018: outline support times contrast): the
//     fraction of the ellipse's outline supported by edge points times the pupil/iris
//     contrast, clamped to 0..1. Below min_confidence nothing is reported: found = false,
//     confidence 0 and a reason (empty frame, no dark region, closed eye...), never a guess.
// Deterministic (the RANSAC sampler is seeded). Accepts CV_8U grey, CV_8UC3/4 (BGR) and
// CV_32F/CV_32FC3 in 0..1.

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "model/gaze/eye_image_renderer.h"

namespace fovea::gaze {

struct PupilDetectorOptions {
  double min_diameter_px = 12, max_diameter_px = 150;
  double min_confidence = 0.4;
  double min_contrast_dn = 20;  // proposal: surround minus centre, 8-bit levels
  int ransac_iterations = 60;
  std::uint32_t seed = 1;
};

struct PupilDetection {
  bool found = false;
  double confidence = 0;
  EyeEllipse ellipse;                  // valid when found
  std::vector<cv::Point2d> glints_px;  // bright corneal reflections near the pupil
  std::string reason;                  // why nothing was found
};

PupilDetection detectPupil(const cv::Mat& image, const PupilDetectorOptions& options = {});

// Converts any accepted input to CV_8U grey (empty Mat when the type is not accepted).
cv::Mat toGrey8(const cv::Mat& image);

}  // namespace fovea::gaze

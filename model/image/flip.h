#pragma once
// LDR-FLIP (Andersson, Nilsson, Akenine-Moeller, Oskarsson, Astrom, Fairchild, "FLIP: A
// Difference Evaluator for Alternating Images", Proc. ACM Comput. Graph. Interact. Tech.
// (HPG) 3(2), 2020): a per-pixel perceptual difference in [0, 1] between a reference and a
// test image seen at a given number of pixels per degree.
//  - colour pipeline: sRGB -> linear -> XYZ -> YyCxCz opponent space, spatial filtering by
//    the contrast sensitivity functions (achromatic, red-green, blue-yellow: sums of
//    Gaussians, Sec. 4.1), back to linear RGB clamped to [0, 1], CIELAB with the Hunt
//    adjustment (a, b scaled by 0.01 L), HyAB distance, raised to q_c = 0.7 and remapped
//    to [0, 1] against the distance between Hunt-adjusted green and blue with the
//    compression p_c = 0.4, p_t = 0.95 (Sec. 4.2);
//  - feature pipeline: edges (first Gaussian derivative) and points (second derivative)
//    of the normalised achromatic channel, sigma = 0.5 w ppd with w = 0.082 deg, feature
//    difference max(|dEdge|, |dPoint|)/sqrt(2) raised to q_f = 0.5 (Sec. 4.3);
//  - combination dE = dE_c ^ (1 - dE_f) (Eq. 9).
// Written from the paper's equations; not bit-identical to NVIDIA's reference code.

#include <opencv2/core.hpp>

namespace fovea::image {

// reference and test: CV_32FC3 sRGB-encoded RGB in [0, 1], same size. Returns CV_32FC1.
cv::Mat flipErrorMap(const cv::Mat& reference_srgb, const cv::Mat& test_srgb, double pixels_per_degree);

}  // namespace fovea::image

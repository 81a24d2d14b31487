#pragma once
// A synthetic target image for the foveated preview: it shows what each display can
// resolve. Linear RGB CV_32FC3 of `size` spanning `fov_deg` (equal-angle grid):
//  - a chirp (zone plate) in luminance whose local frequency grows from 0 at the centre
//    to `max_cpd` cycles/deg at the image's half-width, so the peripheral display's
//    Nyquist limit shows as the ring where it blurs or aliases;
//  - a hue that turns with the polar angle (saturation 0.5), for the colour match;
//  - thin grey lines every 5 deg of yaw and pitch, for the geometry.
#include <array>

#include <opencv2/core.hpp>

namespace fovea::image {

cv::Mat makeTestTarget(cv::Size size, std::array<double, 2> fov_deg, double max_cpd);

}  // namespace fovea::image

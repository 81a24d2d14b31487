#pragma once
// Image files for the preview through OpenImageIO: any format it reads (PNG, JPEG, TIFF,
// EXR, ...), converted to linear-light float RGB (the displays add light, so blending
// happens in linear light), and written back sRGB-encoded.

#include <stdexcept>
#include <string>

#include <opencv2/core.hpp>

namespace fovea::image {

class ImageIoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// CV_32FC3 (R, G, B order), linear light in [0, 1]. 8/16-bit and other integer files are
// taken as sRGB-encoded; float files (EXR, HDR) as linear. Throws ImageIoError naming the
// file and the reason.
cv::Mat readLinearRgb(const std::string& path);
// Writes a CV_32FC3 linear RGB image, sRGB-encoded to 8 bits (16 for .tif/.png with
// `sixteen_bit`), or as float for .exr. Throws ImageIoError.
void writeLinearRgb(const std::string& path, const cv::Mat& linear_rgb, bool sixteen_bit = false);

}  // namespace fovea::image

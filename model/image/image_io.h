#pragma once
// Image files for the preview through OpenImageIO: any format it reads (PNG, JPEG, TIFF,
// EXR, ...), converted to linear-light float RGB (the displays add light, so blending
// happens in linear light), and written back sRGB-encoded; and the bench's camera frames
// (grey, as captured). OpenImageIO is loaded on the first call (model/image/image_codec.h).

#include <cstddef>
#include <stdexcept>
#include <string>

#include <opencv2/core.hpp>

namespace fovea::image {

class ImageIoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Input limits: a regular file (a FIFO or a device such as /dev/zero is refused) of at most
// kMaxImageFileBytes, whose header declares at most kMaxImagePixels pixels (checked before any
// pixel is decoded: a small PNG may declare 20000 x 20000), and a JPEG must be complete (end with
// its EOI marker: a truncated one decodes to grey without an error).
inline constexpr std::size_t kMaxImageFileBytes = std::size_t{512} << 20;
inline constexpr double kMaxImagePixels = 50e6;

// The checks above on the file and its header, without decoding: throws ImageIoError
// "PATH: problem". For readers other than readLinearRgb and readCameraImage.
void checkImageFile(const std::string& path);

// CV_32FC3 (R, G, B order), linear light in [0, 1]. 8/16-bit and other integer files are
// taken as sRGB-encoded; float files (EXR, HDR) as linear. Throws ImageIoError naming the
// file and the reason.
cv::Mat readLinearRgb(const std::string& path);
// Writes a CV_32FC3 linear RGB image, sRGB-encoded to 8 bits (16 for .tif/.png with
// `sixteen_bit`), or as float for .exr. Encoded in memory and written by the one writer
// (model/io/output_file.h: a device, FIFO or directory refused, atomic rename, every write
// checked); a format that cannot encode to memory is staged in a private temporary directory
// first, so every format goes through that writer.
// Throws ImageIoError.
void writeLinearRgb(const std::string& path, const cv::Mat& linear_rgb, bool sixteen_bit = false);

// A camera frame file as 8-bit grey (CV_8UC1): grey files as stored (16-bit ones scaled to 8),
// colour ones by cv::IMREAD_GRAYSCALE's weights. The checks above first. Throws ImageIoError.
cv::Mat readCameraImage(const std::string& path);
// Writes a one-channel CV_8U or CV_16U camera frame as is (PNG, TIFF, ... by the file name),
// through the one writer like writeLinearRgb. Throws ImageIoError.
void writeCameraImage(const std::string& path, const cv::Mat& image);

}  // namespace fovea::image

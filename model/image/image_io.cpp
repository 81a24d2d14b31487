#include "model/image/image_io.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <OpenImageIO/imageio.h>

#include "model/color/srgb.h"

namespace fovea::image {

cv::Mat readLinearRgb(const std::string& path) {
  if (!std::filesystem::exists(path)) throw ImageIoError(path + ": no such file");
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw ImageIoError(path + ": unsupported or unreadable image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  const int w = spec.width, h = spec.height, nc = spec.nchannels;
  if (w <= 0 || h <= 0 || nc <= 0) throw ImageIoError(path + ": image has no pixels");
  std::vector<float> pixels(static_cast<std::size_t>(w) * h * nc);
  if (!in->read_image(0, 0, 0, nc, OIIO::TypeDesc::FLOAT, pixels.data()))
    throw ImageIoError(path + ": cannot decode the image: " + in->geterror());
  const bool isFloat = spec.format.basetype == OIIO::TypeDesc::FLOAT || spec.format.basetype == OIIO::TypeDesc::HALF ||
                       spec.format.basetype == OIIO::TypeDesc::DOUBLE;
  in->close();
  // Lookup table for the sRGB decode of integer images.
  cv::Mat out(h, w, CV_32FC3);
  for (int y = 0; y < h; ++y) {
    auto* row = out.ptr<cv::Vec3f>(y);
    for (int x = 0; x < w; ++x) {
      const float* p = &pixels[(static_cast<std::size_t>(y) * w + x) * nc];
      cv::Vec3f v = nc >= 3 ? cv::Vec3f(p[0], p[1], p[2]) : cv::Vec3f(p[0], p[0], p[0]);
      if (!isFloat)
        for (int c = 0; c < 3; ++c) v[c] = color::srgbToLinear(v[c]);
      for (int c = 0; c < 3; ++c)
        if (!std::isfinite(v[c])) throw ImageIoError(path + ": image holds non-finite pixel values");
      row[x] = v;
    }
  }
  return out;
}

void writeLinearRgb(const std::string& path, const cv::Mat& img, bool sixteen_bit) {
  if (img.type() != CV_32FC3) throw ImageIoError(path + ": internal: expected a float RGB image");
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw ImageIoError(path + ": no image format for this file name: " + OIIO::geterror());
  const std::string ext = std::filesystem::path(path).extension().string();
  const bool isFloat = ext == ".exr" || ext == ".EXR" || ext == ".hdr";
  const OIIO::TypeDesc type = isFloat       ? OIIO::TypeDesc::FLOAT
                              : sixteen_bit ? OIIO::TypeDesc::UINT16
                                            : OIIO::TypeDesc::UINT8;
  OIIO::ImageSpec spec(img.cols, img.rows, 3, type);
  std::vector<float> data(static_cast<std::size_t>(img.cols) * img.rows * 3);
  for (int y = 0; y < img.rows; ++y) {
    const auto* row = img.ptr<cv::Vec3f>(y);
    for (int x = 0; x < img.cols; ++x)
      for (int c = 0; c < 3; ++c) {
        const float v = row[x][c];
        data[(static_cast<std::size_t>(y) * img.cols + x) * 3 + c] = isFloat ? v : color::linearToSrgb(v);
      }
  }
  if (!out->open(path, spec)) throw ImageIoError(path + ": cannot open for writing: " + out->geterror());
  if (!out->write_image(OIIO::TypeDesc::FLOAT, data.data()))
    throw ImageIoError(path + ": cannot write the image: " + out->geterror());
  if (!out->close()) throw ImageIoError(path + ": cannot finish the file: " + out->geterror());
}

}  // namespace fovea::image

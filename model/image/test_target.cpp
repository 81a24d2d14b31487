#include "model/image/test_target.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "model/color/srgb.h"
#include "model/image/image_io.h"

namespace fovea::image {

cv::Mat makeTestTarget(cv::Size size, std::array<double, 2> fov, double max_cpd) {
  cv::Mat out(size, CV_32FC3);
  const double pi = std::numbers::pi, half = 0.5 * fov[0];
  // Chirp cos(pi k r^2): local frequency d(phase)/dr / (2 pi) = k r, so k = max_cpd / half.
  const double k = max_cpd / half;
  const double degPerPx = fov[0] / size.width;
  for (int y = 0; y < size.height; ++y) {
    auto* row = out.ptr<cv::Vec3f>(y);
    const double pitch = (0.5 - (y + 0.5) / size.height) * fov[1];
    for (int x = 0; x < size.width; ++x) {
      const double yaw = ((x + 0.5) / size.width - 0.5) * fov[0];
      const double r2 = yaw * yaw + pitch * pitch;
      const double lum = 0.5 + 0.4 * std::cos(pi * k * r2);  // sRGB-encoded level
      const double hue = std::atan2(pitch, yaw);
      cv::Vec3f c;
      for (int ch = 0; ch < 3; ++ch) {
        const double tint = 1.0 + 0.5 * std::cos(hue - ch * 2.0 * pi / 3.0) * std::min(1.0, std::sqrt(r2) / 4.0);
        c[ch] = color::srgbToLinear(static_cast<float>(std::clamp(lum * tint / 1.5, 0.0, 1.0)));
      }
      const bool line =
          std::abs(std::remainder(yaw, 5.0)) < 0.5 * degPerPx || std::abs(std::remainder(pitch, 5.0)) < 0.5 * degPerPx;
      row[x] = line ? cv::Vec3f(0.2f, 0.2f, 0.2f) : c;
    }
  }
  return out;
}

}  // namespace fovea::image

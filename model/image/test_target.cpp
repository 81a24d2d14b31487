#include "model/image/test_target.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <numbers>
#include <optional>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "model/color/srgb.h"
#include "model/image/image_io.h"

namespace fovea::image {

namespace {

cv::Mat renderTestTarget(cv::Size size, std::array<double, 2> fov, double max_cpd) {
  cv::Mat out(size, CV_32FC3);
  const double pi = std::numbers::pi;
  // Chirp cos(pi k r^2): local frequency d(phase)/dr / (2 pi) = k r, so k = max_cpd / half.
  const double k = max_cpd / (0.5 * fov[0]);
  const double degPerPx = fov[0] / size.width;
  // Rows in parallel: each pixel is a function of its own coordinates only, so the image is the
  // same whatever the split.
  tbb::parallel_for(tbb::blocked_range<int>(0, size.height, 16), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y) {
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
        const bool line = std::abs(std::remainder(yaw, 5.0)) < 0.5 * degPerPx ||
                          std::abs(std::remainder(pitch, 5.0)) < 0.5 * degPerPx;
        row[x] = line ? cv::Vec3f(0.2f, 0.2f, 0.2f) : c;
      }
    }
  });
  return out;
}

}  // namespace

cv::Mat makeTestTarget(cv::Size size, std::array<double, 2> fov, double max_cpd) {
  // The last target made, kept: the studio's preview makes the same 1920 x 1080 target for every
  // scene (and every main window) with the same FOV, ~0.5 CPU-s each time. A copy is returned,
  // so a caller may draw on its target.
  struct Key {
    cv::Size size;
    std::array<double, 2> fov;
    double max_cpd;
    bool operator==(const Key&) const = default;
  };
  static std::mutex mutex;
  static std::optional<std::pair<Key, cv::Mat>> last;
  const Key key{size, fov, max_cpd};
  {
    std::lock_guard lock(mutex);
    if (last && last->first == key) return last->second.clone();
  }
  cv::Mat made = renderTestTarget(size, fov, max_cpd);
  std::lock_guard lock(mutex);
  last.emplace(key, made);
  return made.clone();
}

}  // namespace fovea::image

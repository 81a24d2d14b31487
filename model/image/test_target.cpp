#include "model/image/test_target.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <numbers>
#include <optional>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "model/color/srgb.h"
#include "model/image/image_io.h"

namespace fovea::image {

namespace {

// Per column (yaw) and per row (pitch): the coordinate, whether a 5-degree line passes through
// it, and the chirp's phase pi k t^2 as a unit complex number, so that per pixel
// cos(pi k (yaw^2 + pitch^2)) = Re(e^{i pi k yaw^2} e^{i pi k pitch^2}) and the hue's
// cos(hue - c) = (yaw cos c + pitch sin c) / r need no trigonometric call (issue 25: the
// 2 million cosines, atan2s and remainders were most of a studio start's CPU; the values agree
// with the direct formulas to ~1e-13: 2 of the 13.5 million floats of four test targets differ).
struct Axis {
  std::vector<double> t, cos_phase, sin_phase;
  std::vector<bool> line;
};

Axis axisSamples(int n, double extent_deg, double k, double deg_per_px, bool up) {
  Axis a;
  for (int i = 0; i < n; ++i) {
    const double t = up ? (0.5 - (i + 0.5) / n) * extent_deg : ((i + 0.5) / n - 0.5) * extent_deg;
    const double phase = std::numbers::pi * k * t * t;
    a.t.push_back(t);
    a.cos_phase.push_back(std::cos(phase));
    a.sin_phase.push_back(std::sin(phase));
    a.line.push_back(std::abs(std::remainder(t, 5.0)) < 0.5 * deg_per_px);
  }
  return a;
}

cv::Mat renderTestTarget(cv::Size size, std::array<double, 2> fov, double max_cpd) {
  cv::Mat out(size, CV_32FC3);
  // Chirp cos(pi k r^2): local frequency d(phase)/dr / (2 pi) = k r, so k = max_cpd / half.
  const double k = max_cpd / (0.5 * fov[0]);
  const double degPerPx = fov[0] / size.width;
  const Axis yaw = axisSamples(size.width, fov[0], k, degPerPx, false);
  const Axis pitch = axisSamples(size.height, fov[1], k, degPerPx, true);
  // The three channels' hue offsets c = 0, 120, 240 degrees.
  const double half_sqrt3 = 0.5 * std::sqrt(3.0);
  const std::array<double, 3> cos_c{1.0, -0.5, -0.5}, sin_c{0.0, half_sqrt3, -half_sqrt3};
  // Rows in parallel: each pixel is a function of its own coordinates only, so the image is the
  // same whatever the split.
  tbb::parallel_for(tbb::blocked_range<int>(0, size.height, 16), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y) {
      auto* row = out.ptr<cv::Vec3f>(y);
      const double p = pitch.t[y];
      for (int x = 0; x < size.width; ++x) {
        if (yaw.line[x] || pitch.line[y]) {  // thin grey lines every 5 deg
          row[x] = cv::Vec3f(0.2f, 0.2f, 0.2f);
          continue;
        }
        const double w = yaw.t[x];
        const double r2 = w * w + p * p, r = std::sqrt(r2);
        const double chirp = yaw.cos_phase[x] * pitch.cos_phase[y] - yaw.sin_phase[x] * pitch.sin_phase[y];
        const double lum = 0.5 + 0.4 * chirp;  // sRGB-encoded level
        // cos(hue - c) * min(1, r / 4) with hue = atan2(pitch, yaw); at r = 0 the factor is 0.
        const double scale = r > 0 ? std::min(1.0, r / 4.0) / r : 0.0;
        cv::Vec3f c;
        for (std::size_t ch = 0; ch < 3; ++ch) {
          const double tint = 1.0 + 0.5 * (w * cos_c[ch] + p * sin_c[ch]) * scale;
          c[static_cast<int>(ch)] = color::srgbToLinear(static_cast<float>(std::clamp(lum * tint / 1.5, 0.0, 1.0)));
        }
        row[x] = c;
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

#include "model/color/luminance_curve.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace fovea::color {

namespace {
// Pool-adjacent-violators: least-squares non-decreasing fit.
std::vector<double> isotonic(const std::vector<double>& y) {
  struct Block {
    double sum;
    int count;
  };
  std::vector<Block> blocks;
  for (double v : y) {
    blocks.push_back({v, 1});
    while (blocks.size() > 1) {
      const Block& b = blocks.back();
      const Block& a = blocks[blocks.size() - 2];
      if (a.sum / a.count <= b.sum / b.count) break;
      Block merged{a.sum + b.sum, a.count + b.count};
      blocks.pop_back();
      blocks.back() = merged;
    }
  }
  std::vector<double> out;
  out.reserve(y.size());
  for (const Block& b : blocks) out.insert(out.end(), b.count, b.sum / b.count);
  return out;
}
}  // namespace

LuminanceCurve::LuminanceCurve(const std::vector<double>& measured) {
  if (measured.size() < 2) throw std::invalid_argument("a luminance curve needs at least 2 samples");
  for (double v : measured)
    if (!std::isfinite(v)) throw std::invalid_argument("luminance curve holds a non-finite value");
  values_ = isotonic(measured);
  black_ = values_.front();
  for (double& v : values_) v -= black_;
  const std::size_t n = values_.size();
  // Fritsch-Carlson tangents on unit spacing.
  std::vector<double> delta(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) delta[i] = values_[i + 1] - values_[i];
  slopes_.assign(n, 0.0);
  slopes_[0] = delta[0];
  slopes_[n - 1] = delta[n - 2];
  for (std::size_t i = 1; i + 1 < n; ++i)
    slopes_[i] = (delta[i - 1] * delta[i] <= 0.0) ? 0.0 : 2.0 / (1.0 / delta[i - 1] + 1.0 / delta[i]);  // harmonic mean
  for (std::size_t i = 0; i + 1 < n; ++i) {
    if (delta[i] == 0.0) {
      slopes_[i] = slopes_[i + 1] = 0.0;
      continue;
    }
    const double a = slopes_[i] / delta[i], b = slopes_[i + 1] / delta[i];
    const double s = a * a + b * b;
    if (s > 9.0) {
      const double t = 3.0 / std::sqrt(s);
      slopes_[i] = t * a * delta[i];
      slopes_[i + 1] = t * b * delta[i];
    }
  }
}

double LuminanceCurve::luminance(double code) const {
  const double c = std::clamp(code, 0.0, maxCode());
  const std::size_t i = std::min(static_cast<std::size_t>(c), values_.size() - 2);
  const double t = c - static_cast<double>(i);
  const double t2 = t * t, t3 = t2 * t;
  // Cubic Hermite basis on unit spacing.
  return (2 * t3 - 3 * t2 + 1) * values_[i] + (t3 - 2 * t2 + t) * slopes_[i] + (-2 * t3 + 3 * t2) * values_[i + 1] +
         (t3 - t2) * slopes_[i + 1];
}

double LuminanceCurve::code(double lum) const {
  if (lum <= 0.0) return 0.0;
  if (lum >= peakLuminance()) {
    // The first code reaching the peak (a saturated curve has a plateau).
    auto it = std::lower_bound(values_.begin(), values_.end(), peakLuminance());
    return static_cast<double>(it - values_.begin());
  }
  // Bracket by the samples, then bisect the monotone Hermite segment.
  auto it = std::lower_bound(values_.begin(), values_.end(), lum);
  double hi = static_cast<double>(it - values_.begin());
  double lo = std::max(0.0, hi - 1.0);
  for (int k = 0; k < 60; ++k) {
    const double mid = 0.5 * (lo + hi);
    (luminance(mid) < lum ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace fovea::color

#pragma once
// One display channel's measured luminance curve (seed B.2.2: 256 steps, Y[i] the luminance
// of that channel alone at code value i) as a monotone function of a real code value, and
// its inverse (the look-up table that turns a wanted luminance into a drive value).

#include <vector>

namespace fovea::color {

class LuminanceCurve {
 public:
  LuminanceCurve() = default;
  // `measured` holds >= 2 samples at codes 0, 1, ..., n-1 (the seed's n = 256). The black
  // level Y[0] is subtracted (it is emitted whatever the drive, so it does not mix), the
  // samples are made non-decreasing by isotonic regression (pool-adjacent-violators:
  // the least-squares monotone fit, robust to measurement noise), and interpolated by
  // monotone piecewise-cubic Hermite (Fritsch & Carlson 1980), so no overshoot.
  explicit LuminanceCurve(const std::vector<double>& measured);

  double maxCode() const { return static_cast<double>(values_.size()) - 1.0; }
  double peakLuminance() const { return values_.empty() ? 0.0 : values_.back(); }
  double blackLevel() const { return black_; }
  // Luminance above black at a real code value in [0, maxCode()] (clamped).
  double luminance(double code) const;
  // Smallest code value whose luminance reaches `luminance` (clamped to [0, peak]).
  double code(double luminance) const;
  const std::vector<double>& monotoneSamples() const { return values_; }

 private:
  std::vector<double> values_;  // monotone, black-subtracted samples
  std::vector<double> slopes_;  // Fritsch-Carlson tangents at the samples
  double black_ = 0;
};

}  // namespace fovea::color

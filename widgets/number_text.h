#pragma once
// Numbers as the studio's summaries and reports print them: significant digits or a
// percentage, and an em dash for a value that is not finite (not computed, no data).
#include <QString>

#include <cmath>

namespace fovea::widgets {

inline QString numberText(double v, int significant = 4) {
  return std::isfinite(v) ? QString::number(v, 'g', significant) : QStringLiteral("—");
}

inline QString percentText(double fraction) {
  return std::isfinite(fraction) ? QString::number(100.0 * fraction, 'f', 1) + " %" : QStringLiteral("—");
}

}  // namespace fovea::widgets

#pragma once
// Perceptual comparison of a rendered image with a baseline PNG, tolerant of what differs
// between machines (Mesa llvmpipe rasterisation, anti-aliasing, font hinting) and strict
// about what a user would notice (a missing ray fan, a wrong colour, a moved element):
// both images are box-filtered down by 4 (each output pixel the mean of 4 x 4 pixels), then
// compared in CIELAB; the images match when the mean colour difference dE76 stays below
// mean_limit and at most outlier_fraction of the pixels differ by more than outlier_dE.

#include <QImage>
#include <QPainter>

#include <QString>
#include <algorithm>
#include <array>

#include <cmath>

#include "model/color/srgb.h"

namespace fovea::test {

struct ImageDifference {
  bool same_size = false;
  double mean_dE = 0;
  double outlier_fraction = 0;
  QImage diff;  // downscaled, brighter where they differ
};

inline std::array<double, 3> toLab(QRgb c) {
  const Eigen::Vector3d lab = color::srgbToLab(Eigen::Vector3d(qRed(c), qGreen(c), qBlue(c)) / 255.0);
  return {lab[0], lab[1], lab[2]};
}

inline QImage boxDown(const QImage& in, int k) {
  const QImage src = in.convertToFormat(QImage::Format_RGB32);
  QImage out(src.width() / k, src.height() / k, QImage::Format_RGB32);
  for (int y = 0; y < out.height(); ++y)
    for (int x = 0; x < out.width(); ++x) {
      int r = 0, g = 0, b = 0;
      for (int j = 0; j < k; ++j)
        for (int i = 0; i < k; ++i) {
          const QRgb c = src.pixel(x * k + i, y * k + j);
          r += qRed(c);
          g += qGreen(c);
          b += qBlue(c);
        }
      const int n = k * k;
      out.setPixel(x, y, qRgb(r / n, g / n, b / n));
    }
  return out;
}

inline ImageDifference compareImages(const QImage& actual, const QImage& baseline, double outlier_dE = 20.0) {
  ImageDifference d;
  d.same_size = actual.size() == baseline.size();
  if (!d.same_size) return d;
  const QImage a = boxDown(actual, 4), b = boxDown(baseline, 4);
  d.diff = QImage(a.size(), QImage::Format_RGB32);
  double sum = 0;
  int outliers = 0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) {
      const auto la = toLab(a.pixel(x, y)), lb = toLab(b.pixel(x, y));
      const double dE = std::sqrt((la[0] - lb[0]) * (la[0] - lb[0]) + (la[1] - lb[1]) * (la[1] - lb[1]) +
                                  (la[2] - lb[2]) * (la[2] - lb[2]));
      sum += dE;
      if (dE > outlier_dE) ++outliers;
      const int v = std::min(255, static_cast<int>(dE * 5));
      d.diff.setPixel(x, y, qRgb(v, v, v));
    }
  const double n = static_cast<double>(a.width()) * a.height();
  d.mean_dE = sum / n;
  d.outlier_fraction = outliers / n;
  return d;
}

}  // namespace fovea::test

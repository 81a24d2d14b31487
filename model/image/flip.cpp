#include "model/image/flip.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "model/color/srgb.h"
#include "model/image/image_io.h"
#include "model/units.h"

namespace fovea::image {

namespace {
// sRGB (D65) linear RGB <-> XYZ, white Y = 1.
cv::Matx33f rgbToXyzMatrix() {
  cv::Matx33f m;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m(r, c) = static_cast<float>(color::kLinearSrgbToXyz[r][c]);
  return m;
}
const cv::Matx33f kRgbToXyz = rgbToXyzMatrix();
const cv::Vec3f kWhite(static_cast<float>(color::kSrgbWhiteXyz[0]), static_cast<float>(color::kSrgbWhiteXyz[1]),
                       static_cast<float>(color::kSrgbWhiteXyz[2]));

cv::Vec3f xyzToYcxcz(const cv::Vec3f& xyz) {
  const float yr = xyz[1] / kWhite[1];
  return {116.0f * yr - 16.0f, 500.0f * (xyz[0] / kWhite[0] - yr), 200.0f * (yr - xyz[2] / kWhite[2])};
}
cv::Vec3f ycxczToXyz(const cv::Vec3f& v) {
  const float yr = (v[0] + 16.0f) / 116.0f;
  return {kWhite[0] * (v[1] / 500.0f + yr), kWhite[1] * yr, kWhite[2] * (yr - v[2] / 200.0f)};
}
cv::Vec3f xyzToLab(const cv::Vec3f& xyz) {
  const auto f = color::labCompand<float>;
  const float fx = f(xyz[0] / kWhite[0]), fy = f(xyz[1] / kWhite[1]), fz = f(xyz[2] / kWhite[2]);
  return {116 * fy - 16, 500 * (fx - fy), 200 * (fy - fz)};
}
cv::Vec3f huntLab(const cv::Vec3f& linearRgb) {
  cv::Vec3f lab = xyzToLab(kRgbToXyz * linearRgb);
  lab[1] *= 0.01f * lab[0];
  lab[2] *= 0.01f * lab[0];
  return lab;
}
double hyab(const cv::Vec3f& a, const cv::Vec3f& b) {
  return std::abs(a[0] - b[0]) + std::hypot(a[1] - b[1], a[2] - b[2]);
}

// CSF kernel of one opponent channel: sum of Gaussians a_i sqrt(pi/b_i) exp(-pi^2 x^2/b_i)
// (x in degrees), sampled at 1/ppd and normalised to unit sum (Sec. 4.1, Table 1).
cv::Mat csfKernel(double a1, double b1, double a2, double b2, double ppd) {
  const double maxB = std::max(b1, b2);
  const int radius = static_cast<int>(std::ceil(3.0 * std::sqrt(maxB / (2.0 * kPi * kPi)) * ppd));
  const int n = 2 * radius + 1;
  cv::Mat k(n, n, CV_32F);
  double sum = 0;
  for (int y = -radius; y <= radius; ++y)
    for (int x = -radius; x <= radius; ++x) {
      const double r2 = (x * x + y * y) / (ppd * ppd);
      double v = a1 * std::sqrt(kPi / b1) * std::exp(-kPi * kPi * r2 / b1);
      if (a2 > 0) v += a2 * std::sqrt(kPi / b2) * std::exp(-kPi * kPi * r2 / b2);
      k.at<float>(y + radius, x + radius) = static_cast<float>(v);
      sum += v;
    }
  return k / sum;
}

// Colour-filtered, Hunt-adjusted CIELAB image of an sRGB image.
cv::Mat filteredHuntLab(const cv::Mat& srgb, double ppd) {
  cv::Mat opp(srgb.size(), CV_32FC3);
  for (int y = 0; y < srgb.rows; ++y)
    for (int x = 0; x < srgb.cols; ++x) {
      const cv::Vec3f& s = srgb.at<cv::Vec3f>(y, x);
      const cv::Vec3f lin(color::srgbToLinear(s[0]), color::srgbToLinear(s[1]), color::srgbToLinear(s[2]));
      opp.at<cv::Vec3f>(y, x) = xyzToYcxcz(kRgbToXyz * lin);
    }
  std::vector<cv::Mat> ch;
  cv::split(opp, ch);
  cv::filter2D(ch[0], ch[0], -1, csfKernel(1.0, 0.0047, 0.0, 1e-5, ppd), {-1, -1}, 0, cv::BORDER_REPLICATE);
  cv::filter2D(ch[1], ch[1], -1, csfKernel(1.0, 0.0053, 0.0, 1e-5, ppd), {-1, -1}, 0, cv::BORDER_REPLICATE);
  cv::filter2D(ch[2], ch[2], -1, csfKernel(34.1, 0.04, 13.5, 0.025, ppd), {-1, -1}, 0, cv::BORDER_REPLICATE);
  cv::merge(ch, opp);
  const cv::Matx33f xyzToRgb = kRgbToXyz.inv();
  cv::Mat lab(srgb.size(), CV_32FC3);
  for (int y = 0; y < srgb.rows; ++y)
    for (int x = 0; x < srgb.cols; ++x) {
      cv::Vec3f rgb = xyzToRgb * ycxczToXyz(opp.at<cv::Vec3f>(y, x));
      for (int c = 0; c < 3; ++c) rgb[c] = std::clamp(rgb[c], 0.0f, 1.0f);
      lab.at<cv::Vec3f>(y, x) = huntLab(rgb);
    }
  return lab;
}

// Edge and point feature magnitudes of the normalised achromatic channel.
void features(const cv::Mat& srgb, double ppd, cv::Mat& edge, cv::Mat& point) {
  cv::Mat yn(srgb.size(), CV_32F);
  for (int y = 0; y < srgb.rows; ++y)
    for (int x = 0; x < srgb.cols; ++x) {
      const cv::Vec3f& s = srgb.at<cv::Vec3f>(y, x);
      const cv::Vec3f lin(color::srgbToLinear(s[0]), color::srgbToLinear(s[1]), color::srgbToLinear(s[2]));
      yn.at<float>(y, x) = (xyzToYcxcz(kRgbToXyz * lin)[0] + 16.0f) / 116.0f;
    }
  const double sigma = 0.5 * 0.082 * ppd;
  const int radius = static_cast<int>(std::ceil(3 * sigma));
  const int n = 2 * radius + 1;
  cv::Mat g(1, n, CV_32F), d1(1, n, CV_32F), d2(1, n, CV_32F);
  double gs = 0;
  for (int i = -radius; i <= radius; ++i) gs += std::exp(-i * i / (2 * sigma * sigma));
  // Derivative kernels normalised so their positive and negative parts each sum to +-1.
  double p1 = 0, p2 = 0, n2 = 0;
  for (int i = -radius; i <= radius; ++i) {
    const double gv = std::exp(-i * i / (2 * sigma * sigma));
    g.at<float>(i + radius) = static_cast<float>(gv / gs);
    const double a = -i * gv, b = (i * i / (sigma * sigma) - 1) * gv;
    d1.at<float>(i + radius) = static_cast<float>(a);
    d2.at<float>(i + radius) = static_cast<float>(b);
    if (a > 0) p1 += a;
    if (b > 0)
      p2 += b;
    else
      n2 -= b;
  }
  d1 /= p1;
  for (int i = 0; i < n; ++i) {
    float& v = d2.at<float>(i);
    v = v > 0 ? static_cast<float>(v / p2) : static_cast<float>(v / n2);
  }
  cv::Mat ex, ey, px, py;
  cv::sepFilter2D(yn, ex, CV_32F, d1, g.t(), {-1, -1}, 0, cv::BORDER_REPLICATE);
  cv::sepFilter2D(yn, ey, CV_32F, g, d1.t(), {-1, -1}, 0, cv::BORDER_REPLICATE);
  cv::sepFilter2D(yn, px, CV_32F, d2, g.t(), {-1, -1}, 0, cv::BORDER_REPLICATE);
  cv::sepFilter2D(yn, py, CV_32F, g, d2.t(), {-1, -1}, 0, cv::BORDER_REPLICATE);
  cv::magnitude(ex, ey, edge);
  cv::magnitude(px, py, point);
}
}  // namespace

cv::Mat flipErrorMap(const cv::Mat& ref, const cv::Mat& test, double ppd) {
  CV_Assert(ref.type() == CV_32FC3 && test.type() == CV_32FC3 && ref.size() == test.size());
  const cv::Mat labR = filteredHuntLab(ref, ppd), labT = filteredHuntLab(test, ppd);
  cv::Mat edgeR, pointR, edgeT, pointT;
  features(ref, ppd, edgeR, pointR);
  features(test, ppd, edgeT, pointT);
  constexpr double qc = 0.7, pc = 0.4, pt = 0.95, qf = 0.5;
  const double cmax = std::pow(hyab(huntLab({0, 1, 0}), huntLab({0, 0, 1})), qc);
  cv::Mat out(ref.size(), CV_32F);
  for (int y = 0; y < ref.rows; ++y)
    for (int x = 0; x < ref.cols; ++x) {
      const double d = std::pow(hyab(labR.at<cv::Vec3f>(y, x), labT.at<cv::Vec3f>(y, x)), qc);
      const double dc = d < pc * cmax ? pt / (pc * cmax) * d : pt + (d - pc * cmax) / (cmax - pc * cmax) * (1 - pt);
      const double df = std::pow(std::max(std::abs(edgeR.at<float>(y, x) - edgeT.at<float>(y, x)),
                                          std::abs(pointR.at<float>(y, x) - pointT.at<float>(y, x))) /
                                     std::sqrt(2.0),
                                 qf);
      out.at<float>(y, x) = static_cast<float>(std::pow(std::min(dc, 1.0), 1.0 - std::min(df, 1.0)));
    }
  return out;
}

}  // namespace fovea::image

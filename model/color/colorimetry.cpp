#include "model/color/colorimetry.h"

#include <cmath>

#include "model/color/srgb.h"
#include "model/units.h"

namespace fovea::color {

Eigen::Vector3d xyYToXyz(Xy c, double Y) {
  if (c.y <= 0) return Eigen::Vector3d::Zero();
  return {c.x * Y / c.y, Y, (1.0 - c.x - c.y) * Y / c.y};
}

Xy xyzToXy(const Eigen::Vector3d& xyz) {
  const double s = xyz.sum();
  if (std::abs(s) < 1e-300) return {0.0, 0.0};
  return {xyz.x() / s, xyz.y() / s};
}

Eigen::Vector3d xyzToLab(const Eigen::Vector3d& xyz, const Eigen::Vector3d& white_xyz) {
  const auto f = labCompand<double>;  // CIE 15:2004 8.2.1
  const double fx = f(xyz.x() / white_xyz.x());
  const double fy = f(xyz.y() / white_xyz.y());
  const double fz = f(xyz.z() / white_xyz.z());
  return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

namespace {
double pow7(double v) {
  const double v2 = v * v;
  return v2 * v2 * v2 * v;
}
}  // namespace

double deltaE2000(const Eigen::Vector3d& lab1, const Eigen::Vector3d& lab2) {
  const double L1 = lab1[0], a1 = lab1[1], b1 = lab1[2];
  const double L2 = lab2[0], a2 = lab2[1], b2 = lab2[2];
  // (2)-(5): a' rescaled by G, which depends on the mean chroma.
  const double C1ab = std::hypot(a1, b1), C2ab = std::hypot(a2, b2);
  const double Cbar = 0.5 * (C1ab + C2ab);
  const double twentyFive7 = 6103515625.0;  // 25^7
  const double G = 0.5 * (1.0 - std::sqrt(pow7(Cbar) / (pow7(Cbar) + twentyFive7)));
  const double a1p = (1.0 + G) * a1, a2p = (1.0 + G) * a2;
  const double C1p = std::hypot(a1p, b1), C2p = std::hypot(a2p, b2);
  auto hue = [](double b, double ap) {
    if (b == 0.0 && ap == 0.0) return 0.0;
    double h = radToDeg(std::atan2(b, ap));
    return h < 0.0 ? h + 360.0 : h;
  };
  const double h1p = hue(b1, a1p), h2p = hue(b2, a2p);
  // (8)-(10): differences.
  const double dLp = L2 - L1;
  const double dCp = C2p - C1p;
  double dhp = 0.0;
  const bool achromatic = C1p * C2p == 0.0;
  if (!achromatic) {
    dhp = h2p - h1p;
    if (dhp > 180.0) dhp -= 360.0;
    if (dhp < -180.0) dhp += 360.0;
  }
  const double dHp = 2.0 * std::sqrt(C1p * C2p) * std::sin(degToRad(dhp / 2.0));
  // (12)-(14): means; the mean hue wraps around 360.
  const double Lbarp = 0.5 * (L1 + L2);
  const double Cbarp = 0.5 * (C1p + C2p);
  double hbarp = h1p + h2p;
  if (!achromatic) {
    if (std::abs(h1p - h2p) <= 180.0)
      hbarp /= 2.0;
    else if (h1p + h2p < 360.0)
      hbarp = (h1p + h2p + 360.0) / 2.0;
    else
      hbarp = (h1p + h2p - 360.0) / 2.0;
  }
  // (15)-(21): weighting functions and the rotation term.
  const double T = 1.0 - 0.17 * std::cos(degToRad(hbarp - 30.0)) + 0.24 * std::cos(degToRad(2.0 * hbarp)) +
                   0.32 * std::cos(degToRad(3.0 * hbarp + 6.0)) - 0.20 * std::cos(degToRad(4.0 * hbarp - 63.0));
  const double dTheta = 30.0 * std::exp(-std::pow((hbarp - 275.0) / 25.0, 2.0));
  const double RC = 2.0 * std::sqrt(pow7(Cbarp) / (pow7(Cbarp) + twentyFive7));
  const double Lm50sq = (Lbarp - 50.0) * (Lbarp - 50.0);
  const double SL = 1.0 + 0.015 * Lm50sq / std::sqrt(20.0 + Lm50sq);
  const double SC = 1.0 + 0.045 * Cbarp;
  const double SH = 1.0 + 0.015 * Cbarp * T;
  const double RT = -std::sin(degToRad(2.0 * dTheta)) * RC;
  const double tL = dLp / SL, tC = dCp / SC, tH = dHp / SH;
  return std::sqrt(tL * tL + tC * tC + tH * tH + RT * tC * tH);
}

}  // namespace fovea::color

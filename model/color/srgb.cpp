#include "model/color/srgb.h"

#include "model/color/colorimetry.h"

namespace fovea::color {

Eigen::Vector3d linearSrgbToXyz(const Eigen::Vector3d& rgb) {
  Eigen::Vector3d xyz;
  for (int r = 0; r < 3; ++r)
    xyz[r] = kLinearSrgbToXyz[r][0] * rgb[0] + kLinearSrgbToXyz[r][1] * rgb[1] + kLinearSrgbToXyz[r][2] * rgb[2];
  return xyz;
}

Eigen::Vector3d srgbToLab(const Eigen::Vector3d& srgb) {
  const Eigen::Vector3d lin(srgbToLinear(srgb[0]), srgbToLinear(srgb[1]), srgbToLinear(srgb[2]));
  return xyzToLab(linearSrgbToXyz(lin), Eigen::Vector3d(kSrgbWhiteXyz[0], kSrgbWhiteXyz[1], kSrgbWhiteXyz[2]));
}

std::array<double, 3> wavelengthColor(double nm) {
  if (!(nm >= 380 && nm <= 780)) return {0.35, 0.35, 0.35};
  double r = 0, g = 0, b = 0;
  if (nm < 440) {
    r = (440 - nm) / 60.0;
    b = 1;
  } else if (nm < 490) {
    g = (nm - 440) / 50.0;
    b = 1;
  } else if (nm < 510) {
    g = 1;
    b = (510 - nm) / 20.0;
  } else if (nm < 580) {
    r = (nm - 510) / 70.0;
    g = 1;
  } else if (nm < 645) {
    r = 1;
    g = (645 - nm) / 65.0;
  } else {
    r = 1;
  }
  return {r, g, b};
}

}  // namespace fovea::color

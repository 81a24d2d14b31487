#pragma once
// CIE colorimetry used by the display colour calibration (seed B.2.2): chromaticity
// (xyY) <-> tristimulus (XYZ), CIELAB, and the CIEDE2000 colour difference.

#include <array>

#include <Eigen/Core>

namespace fovea::color {

struct Xy {
  double x = 0, y = 0;
};

inline constexpr Xy kD65{0.3127, 0.3290};

// XYZ of a colour with chromaticity (x, y) and luminance Y: X = xY/y, Z = (1-x-y)Y/y.
Eigen::Vector3d xyYToXyz(Xy c, double Y);
// Chromaticity of a tristimulus vector: x = X/(X+Y+Z), y = Y/(X+Y+Z). Black gives (0,0).
Xy xyzToXy(const Eigen::Vector3d& xyz);

// CIELAB (CIE 15:2004) of `xyz` relative to the reference white `white_xyz`.
Eigen::Vector3d xyzToLab(const Eigen::Vector3d& xyz, const Eigen::Vector3d& white_xyz);

// CIEDE2000 total colour difference (kL = kC = kH = 1), as written out in Sharma, Wu,
// Dalal, "The CIEDE2000 color-difference formula: implementation notes, supplementary
// test data, and mathematical observations", Color Res. Appl. 30(1) 2005, Eqs. (1)-(17).
double deltaE2000(const Eigen::Vector3d& lab1, const Eigen::Vector3d& lab2);

}  // namespace fovea::color

#pragma once
// sRGB colour science in one place (IEC 61966-2-1, D65 white): the transfer function, linear
// sRGB -> CIE XYZ, sRGB -> CIELAB, and the display colour of a spectral wavelength. Image
// I/O, the FLIP metric, the 3D view, the plots and the GUI tests' image comparison use it.

#include <algorithm>
#include <array>
#include <cmath>
#include <concepts>

#include <Eigen/Core>

namespace fovea::color {

// Decode an sRGB value (0..1) to linear light, IEC 61966-2-1 Eq. (1).
template <std::floating_point T>
T srgbToLinear(T v) {
  return v <= T(0.04045) ? v / T(12.92) : std::pow((v + T(0.055)) / T(1.055), T(2.4));
}
// Encode linear light (clamped to 0..1) as sRGB, the inverse of srgbToLinear.
template <std::floating_point T>
T linearToSrgb(T v) {
  v = std::clamp(v, T(0), T(1));
  return v <= T(0.0031308) ? T(12.92) * v : T(1.055) * std::pow(v, T(1) / T(2.4)) - T(0.055);
}

// Linear sRGB -> XYZ (white Y = 1), IEC 61966-2-1 Eq. (3) to four digits; rows X, Y, Z.
inline constexpr std::array<std::array<double, 3>, 3> kLinearSrgbToXyz{{
    {0.4124, 0.3576, 0.1805},
    {0.2126, 0.7152, 0.0722},
    {0.0193, 0.1192, 0.9505},
}};
// XYZ of sRGB white (1, 1, 1) through that matrix: the D65 white of the sRGB images.
inline constexpr std::array<double, 3> kSrgbWhiteXyz{0.9505, 1.0, 1.0889};

// The CIELAB companding f(t) = t^(1/3) above (6/29)^3, linear below (CIE 15:2004 8.2.1).
template <std::floating_point T>
T labCompand(T t) {
  constexpr T d = T(6) / T(29);
  return t > d * d * d ? std::cbrt(t) : t / (3 * d * d) + T(4) / T(29);
}

Eigen::Vector3d linearSrgbToXyz(const Eigen::Vector3d& rgb);
// CIELAB of an sRGB-encoded colour (components 0..1) relative to sRGB white.
Eigen::Vector3d srgbToLab(const Eigen::Vector3d& srgb);

// Display colour (sRGB-encoded, 0..1) of a spectral wavelength: a piecewise-linear
// approximation of the spectral colours (D. Bruton, "Color Science", 1996); gray outside
// 380..780 nm. The 3D view, the display dock and the plots all draw a wavelength with it.
std::array<double, 3> wavelengthColor(double nm);

}  // namespace fovea::color

#include "model/image/speckle_grain.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "model/units.h"

namespace fovea::image {

namespace {
constexpr double kRadPerArcmin = kDeg / 60.0;
}  // namespace

double speckleCorrelationAreaArcmin2(double wavelength_nm, double pupil_diameter_mm) {
  const double grain = wavelength_nm * 1e-6 / pupil_diameter_mm / kRadPerArcmin;  // lambda/D, arcmin
  return 4.0 * grain * grain / kPi;
}

double speckleDegreesOfFreedom(double a, double b, double wavelength_nm, double pupil_diameter_mm) {
  if (!(a > 0) || !(b > 0) || !(wavelength_nm > 0) || !(pupil_diameter_mm > 0))
    throw std::invalid_argument("speckle grain: pixel size, wavelength and pupil must be positive");
  const double grain = wavelength_nm * 1e-6 / pupil_diameter_mm / kRadPerArcmin;  // lambda/D, arcmin
  // |mu|^2 = [2 J1(v)/v]^2, v = pi r / grain.
  auto mu2 = [&](double dx, double dy) {
    const double v = kPi * std::hypot(dx, dy) / grain;
    if (v < 1e-8) return 1.0;
    const double j = 2.0 * std::cyl_bessel_j(1.0, v) / v;
    return j * j;
  };
  // Midpoint rule over the quadrant dx in [0, a], dy in [0, b] (the integrand is even in
  // each), steps at most grain/40 and at most 600 per axis, cut at 60 grains: the tail of
  // integral |mu|^2 beyond v holds about 2/(pi v) of Omega_c, 0.3 % at 60 grains.
  const double xa = std::min(a, 60.0 * grain), yb = std::min(b, 60.0 * grain);
  const int nx = std::clamp(static_cast<int>(std::ceil(xa / (grain / 40.0))), 16, 600);
  const int ny = std::clamp(static_cast<int>(std::ceil(yb / (grain / 40.0))), 16, 600);
  const double hx = xa / nx, hy = yb / ny;
  double sum = 0;
  for (int j = 0; j < ny; ++j) {
    const double dy = (j + 0.5) * hy;
    double row = 0;
    for (int i = 0; i < nx; ++i) {
      const double dx = (i + 0.5) * hx;
      row += (a - dx) * mu2(dx, dy);
    }
    sum += (b - dy) * row;
  }
  const double inv_m = 4.0 * sum * hx * hy / (a * a * b * b);
  return 1.0 / std::min(1.0, inv_m);
}

cv::Mat integratedSpeckleField(cv::Size size, double dof, std::uint64_t seed) {
  if (!(dof >= 1.0) || !std::isfinite(dof)) throw std::invalid_argument("speckle: degrees of freedom must be >= 1");
  std::mt19937_64 rng(seed);
  std::gamma_distribution<double> gamma(dof, 1.0 / dof);  // mean 1, variance 1/dof
  cv::Mat f(size, CV_64F);
  for (int y = 0; y < size.height; ++y) {
    double* row = f.ptr<double>(y);
    for (int x = 0; x < size.width; ++x) row[x] = gamma(rng);
  }
  return f;
}

}  // namespace fovea::image

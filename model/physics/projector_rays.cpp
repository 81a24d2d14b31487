#include "model/physics/projector_rays.h"

#include <algorithm>
#include <cmath>

#include "model/scene/scene_geometry.h"
#include "model/units.h"

namespace fovea {

namespace {}

std::array<int, 2> projectorGrid(const Projector& p, int rays) {
  const double th = std::tan(0.5 * p.fov_deg[0] * kDeg), tv = std::tan(0.5 * p.fov_deg[1] * kDeg);
  const double aspect = tv > 0.0 ? th / tv : 1.0;
  const double n = std::max(1, rays);
  int nx = static_cast<int>(std::lround(std::sqrt(n * aspect)));
  nx = std::clamp(nx, 1, std::max(1, p.pixels[0]));
  int ny = static_cast<int>(std::lround(n / nx));
  ny = std::clamp(ny, 1, std::max(1, p.pixels[1]));
  return {nx, ny};
}

Eigen::Vector3d projectorSource(const Projector& p, double source_shift_mm) {
  return toVec(p.pose.position_mm) + Eigen::Vector3d(0.0, 0.0, source_shift_mm);
}

std::vector<ProjectorRay> projectorRays(const Projector& p, int rays) {
  const auto [nx, ny] = projectorGrid(p, rays);
  const Eigen::Matrix3d axes = rotationFromDeg(p.pose.rotation_deg);
  const double th = std::tan(0.5 * p.fov_deg[0] * kDeg), tv = std::tan(0.5 * p.fov_deg[1] * kDeg);
  std::vector<ProjectorRay> out;
  out.reserve(static_cast<std::size_t>(nx) * ny);
  for (int iy = 0; iy < ny; ++iy) {
    const double y = tv * ((2.0 * iy + 1.0) / ny - 1.0);
    for (int ix = 0; ix < nx; ++ix) {
      const double x = th * ((2.0 * ix + 1.0) / nx - 1.0);
      const Eigen::Vector3d local = Eigen::Vector3d(x, y, 1.0).normalized();
      out.push_back({axes * local, {std::atan(x) / kDeg, std::atan(y) / kDeg}, {ix, iy}});
    }
  }
  return out;
}

PixelBeamSize pixelBeamFwhm(const PixelBeamModel& m, double throw_mm) {
  const double z = std::max(0.0, throw_mm);
  double long_um;
  if (z <= m.waist_distance_mm && m.waist_distance_mm > 0.0)
    long_um = m.exit_fwhm_um + (m.waist_fwhm_um - m.exit_fwhm_um) * z / m.waist_distance_mm;
  else
    long_um = m.waist_fwhm_um + m.divergence_mrad * (z - m.waist_distance_mm);
  const double scale = m.waist_distance_mm > 0.0 ? m.waist_distance_mm : 1.0;
  const double ellipticity = 1.0 + (m.exit_ellipticity - 1.0) * std::exp(-z / scale);
  return {long_um, long_um / ellipticity};
}

}  // namespace fovea

#include "model/physics/lateral_colour.h"

#include <cmath>

#include "model/physics/ray_probe.h"
#include "model/scene/scene_geometry.h"

namespace fovea {

std::size_t calibrationLaser(const std::vector<double>& wavelengths_nm) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < wavelengths_nm.size(); ++i)
    if (std::abs(wavelengths_nm[i] - 555.0) < std::abs(wavelengths_nm[best] - 555.0)) best = i;
  return best;
}

std::vector<LateralColour> lateralColourAtLineOfSight(const Scene& scene, std::array<double, 2> gaze_deg,
                                                      std::array<double, 2> hoe_shift_mm) {
  const auto& lasers = scene.projector.wavelengths_nm;
  std::vector<LateralColour> out(lasers.size());
  for (std::size_t i = 0; i < lasers.size(); ++i) out[i].wavelength_nm = lasers[i];
  if (lasers.empty()) return out;
  RayProbeSetup setup;
  setup.gaze_deg = gaze_deg;
  setup.hoe_shift_mm = hoe_shift_mm;
  const RayProbe probe(scene, setup);
  // Where the line of sight meets the plate plane (a lateral shift keeps the plane).
  const EyePlacement& eye = probe.eye();
  const Frame plate = frameOf(scene.hoe.pose);
  const double denom = eye.gaze.dot(plate.z());
  if (std::abs(denom) < 1e-12) return out;
  const double t = (plate.origin - eye.pupil_center).dot(plate.z()) / denom;
  if (!(t > 0)) return out;
  std::array<double, 2> tan_xy{0, 0};
  if (!probe.aimAt(eye.pupil_center + t * eye.gaze, tan_xy)) return out;
  std::vector<ProbeRay> rays(lasers.size());
  for (std::size_t i = 0; i < lasers.size(); ++i) rays[i] = probe.trace(tan_xy[0], tan_xy[1], lasers[i]);
  const ProbeRay& ref = rays[calibrationLaser(lasers)];
  for (std::size_t i = 0; i < lasers.size(); ++i) {
    out[i].field_deg = rays[i].field_deg;
    out[i].valid = rays[i].in_pupil && ref.in_pupil;
    if (out[i].valid)
      for (int k = 0; k < 2; ++k) out[i].offset_arcmin[k] = 60.0 * (rays[i].field_deg[k] - ref.field_deg[k]);
  }
  return out;
}

}  // namespace fovea

#include "model/analysis/angular_resolution.h"

#include <algorithm>
#include <cmath>

#include "model/physics/display_camera_map.h"
#include "model/scene/scene_geometry.h"
#include "model/units.h"

namespace fovea {

namespace {

Frame shiftedHoeFrame(const Scene& scene, const std::array<double, 2>& shift_mm) {
  Frame f = frameOf(scene.hoe.pose);
  f.origin += f.x() * shift_mm[0] + f.y() * shift_mm[1];
  return f;
}

// Eccentricity range [lo, hi] (deg) where `valid` holds, found by a fine scan then
// bisection of both edges. Empty when nothing is valid.
template <class Valid>
std::optional<std::array<double, 2>> validInterval(Valid&& valid) {
  constexpr double kStep = 0.25;
  std::optional<double> first, last;
  const int steps = static_cast<int>(std::lround(178.0 / kStep));
  for (int i = 0; i <= steps; ++i) {
    const double e = -89.0 + kStep * i;  // exact in binary, as the running sum was
    if (valid(e)) {
      if (!first) first = e;
      last = e;
    }
  }
  if (!first) return std::nullopt;
  auto refine = [&](double inside, double outside) {
    for (int i = 0; i < 50; ++i) {
      const double mid = 0.5 * (inside + outside);
      (valid(mid) ? inside : outside) = mid;
    }
    return inside;
  };
  const double lo = *first - kStep >= -89.0 ? refine(*first, *first - kStep) : *first;
  const double hi = *last + kStep <= 89.0 ? refine(*last, *last + kStep) : *last;
  return std::array<double, 2>{lo, hi};
}
}  // namespace

std::optional<double> projectionAngleForEccentricity(const Scene& scene, double yaw_deg, double pitch_deg,
                                                     double eccentricity_deg, const std::array<double, 2>& hoe_shift_mm,
                                                     bool require_on_hoe) {
  const EyePlacement eye = placeEye(scene, yaw_deg, pitch_deg);
  const Eigen::Vector3d d = gazeDirection(yaw_deg + eccentricity_deg, pitch_deg);
  const Frame hoe = shiftedHoeFrame(scene, hoe_shift_mm);
  const double dn = d.dot(hoe.z());
  if (std::abs(dn) < 1e-12) return std::nullopt;
  const double t = (hoe.origin - eye.pupil_center).dot(hoe.z()) / dn;
  if (t <= 0) return std::nullopt;
  const Eigen::Vector3d x = eye.pupil_center + t * d;
  const Eigen::Vector3d local = hoe.toLocal(x);
  const Frame projector = frameOf(scene.projector.pose);
  const Eigen::Vector3d v = projector.toLocal(x);
  if (v.z() <= 0) return std::nullopt;
  const double phi_deg = std::atan2(v.x(), v.z()) / kDeg;
  if (require_on_hoe) {
    if (std::abs(local.x()) > scene.hoe.size_mm[0] / 2 || std::abs(local.y()) > scene.hoe.size_mm[1] / 2)
      return std::nullopt;
    const double theta_deg = std::atan2(v.y(), v.z()) / kDeg;
    if (std::abs(phi_deg) > scene.projector.fov_deg[0] / 2 || std::abs(theta_deg) > scene.projector.fov_deg[1] / 2)
      return std::nullopt;
  }
  return phi_deg;
}

ResolutionResult analyzeResolution(const Scene& scene, const ResolutionOptions& options) {
  ResolutionResult r;
  const std::array<double, 2> gaze = options.gaze_deg.value_or(scene.eye.gaze_deg);
  const double a = gaze[0], b = gaze[1];
  r.gaze_yaw_deg = a;
  r.gaze_pitch_deg = b;
  r.pixels_horizontal = scene.projector.pixels[0];
  const double k_p = scene.projector.pixels[0] / scene.projector.fov_deg[0];  // S7, pixels per degree of phi
  r.projector_pixels_per_deg = k_p;

  // Peripheral: c_p = (1/2) k_p |dphi/deps| (cycles per degree of eccentricity).
  auto phiFree = [&](double e) { return projectionAngleForEccentricity(scene, a, b, e, options.hoe_shift_mm, false); };
  auto onHoe = [&](double e) {
    return projectionAngleForEccentricity(scene, a, b, e, options.hoe_shift_mm, true).has_value();
  };
  auto peripheralCpd = [&](double e) -> std::optional<double> {
    constexpr double h = 1e-3;
    const auto p1 = phiFree(e + h), p0 = phiFree(e - h);
    if (!p1 || !p0) return std::nullopt;
    return 0.5 * k_p * std::abs(*p1 - *p0) / (2 * h);
  };

  // Foveal: virtual image plane at d_f in front of the zero-gaze pupil (see header).
  const auto& fd = scene.foveal_display;
  const double r_eye = scene.eye.eyeball_diameter_mm / 2;
  const double d_f = fd.combiner.image_distance_mm;
  const double M = fd.combiner.magnification;
  const double image_width = M * fd.size_mm[0];
  const double k_f = fd.pixels[0] / image_width;  // S2, pixels per mm of image plane
  // The image centre on the line of sight: M x_f, the one foveal mapping (display_camera_map.h).
  const double x_c = M * fovealShiftForGaze(scene, {a, 0.0})[0];
  r.foveal_image_shift_mm = x_c;
  const double lever = d_f + r_eye - r_eye * std::cos(a * kDeg);
  const double x_pupil = r_eye * std::sin(a * kDeg);
  auto eccAt = [&](double x) { return std::atan((x - x_pupil) / lever) / kDeg - a; };
  r.foveal_field_deg = {eccAt(x_c - image_width / 2), eccAt(x_c + image_width / 2)};
  auto fovealCpd = [&](double e) -> std::optional<double> {
    if (e < r.foveal_field_deg[0] || e > r.foveal_field_deg[1]) return std::nullopt;
    const double c = std::cos((a + e) * kDeg);
    return 0.5 * k_f * lever / (c * c) * kDeg;  // per radian -> per degree
  };
  auto opticalCpd = [&](double e) {
    const double theta2 = (a + e) * (a + e) + b * b;
    return std::max(0.0, fd.combiner.mtf30_cpd_on_axis * (1.0 - fd.combiner.field_curvature_per_deg2 * theta2));
  };

  const auto field = validInterval(onHoe);
  if (field) {
    r.peripheral_field_deg = *field;
    const auto p_lo = phiFree((*field)[0]), p_hi = phiFree((*field)[1]);
    if (p_lo && p_hi) r.peripheral_pixels_on_hoe = k_p * std::abs(*p_hi - *p_lo);
  }
  const int n = std::max(3, options.samples);
  const double lo = field ? (*field)[0] : r.foveal_field_deg[0];
  const double hi = field ? (*field)[1] : r.foveal_field_deg[1];
  r.samples.reserve(n);
  for (int i = 0; i < n; ++i) {
    ResolutionSample s;
    s.eccentricity_deg = lo + (hi - lo) * i / (n - 1);
    if (field) s.peripheral_cpd = peripheralCpd(s.eccentricity_deg);
    s.foveal_cpd = fovealCpd(s.eccentricity_deg);
    if (s.foveal_cpd) {
      const FovealOpticsSample traced = tracedCombinerMtf30(scene, a, a + s.eccentricity_deg);
      s.optical_limit_cpd = traced.mtf30_cpd;
      s.optical_blur_arcmin = traced.rms_blur_arcmin;
      s.optical_limit_model_cpd = opticalCpd(s.eccentricity_deg);
    }
    s.foveal_shown = s.foveal_cpd && std::abs(s.eccentricity_deg) <= scene.foveation.blend_end_deg;
    if (s.foveal_shown)
      s.perceived_cpd = std::min({*s.foveal_cpd, *s.optical_limit_cpd, kEyeLimitCpd});
    else
      s.perceived_cpd = std::min(s.peripheral_cpd.value_or(0.0), kEyeLimitCpd);
    r.samples.push_back(s);
  }

  // Pixel-count integrals: 2 c integrated over eccentricity (composite Simpson, fine grid).
  auto integrate = [](auto&& f, double x0, double x1) {
    constexpr int m = 2000;
    const double h = (x1 - x0) / m;
    double sum = f(x0) + f(x1);
    for (int i = 1; i < m; ++i) sum += (i % 2 ? 4.0 : 2.0) * f(x0 + i * h);
    return sum * h / 3.0;
  };
  if (field)
    r.peripheral_pixel_integral =
        integrate([&](double e) { return 2.0 * peripheralCpd(e).value_or(0.0); }, (*field)[0], (*field)[1]);
  r.foveal_pixel_integral = integrate(
      [&](double e) {
        const double c = std::cos((a + e) * kDeg);
        return 2.0 * 0.5 * k_f * lever / (c * c) * kDeg;
      },
      r.foveal_field_deg[0], r.foveal_field_deg[1]);
  return r;
}

}  // namespace fovea

#include "model/analysis/foveal_optics.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include <Eigen/Core>

#include "model/scene/scene_geometry.h"
#include "model/units.h"

namespace fovea {

namespace {
constexpr double kWavelengthNm = 550.0;

double diffractionMtf(double nu_cpd, double cutoff_cpd) {
  const double s = nu_cpd / cutoff_cpd;
  if (s >= 1) return 0;
  return 2 / std::numbers::pi * (std::acos(s) - s * std::sqrt(1 - s * s));
}
}  // namespace

// Backward ray from pupil point `p` aimed at `q`; returns the display-plane hit (x, y).
std::optional<Eigen::Vector2d> traceCombinerToDisplay(const CombinerPrescription& c, const Eigen::Vector3d& p,
                                                      const Eigen::Vector3d& q) {
  const Eigen::Vector3d d = (q - p).normalized();
  const double R = 2 * c.focal_length_mm;
  const Eigen::Vector3d centre(0, 0, c.mirror_distance_mm - R);  // concave towards the eye
  const Eigen::Vector3d oc = p - centre;
  const double bq = oc.dot(d), cq = oc.squaredNorm() - R * R;
  const double disc = bq * bq - cq;
  if (disc < 0) return std::nullopt;
  const double t = -bq + std::sqrt(disc);  // the far intersection: the mirror cap near z = b
  if (t <= 0) return std::nullopt;
  const Eigen::Vector3d x = p + t * d;
  const Eigen::Vector3d n = (x - centre) / R;
  const Eigen::Vector3d r = d - 2 * d.dot(n) * n;
  const double z_display = c.mirror_distance_mm - c.display_distance_mm;
  if (std::abs(r.z()) < 1e-12) return std::nullopt;
  const double s = (z_display - x.z()) / r.z();
  if (s <= 0) return std::nullopt;
  const Eigen::Vector3d h = x + s * r;
  return Eigen::Vector2d(h.x(), h.y());
}

std::array<double, 2> fovealFovDeg(const Scene& scene) {
  const FovealDisplay& f = scene.foveal_display;
  const ImageCombiner& c = f.combiner;
  std::array<double, 2> fov{};
  for (int k = 0; k < 2; ++k)
    fov[k] = radToDeg(2.0 * std::atan(c.magnification * f.size_mm[k] / (2.0 * c.image_distance_mm)));
  return fov;
}

CombinerPrescription combinerPrescription(const Scene& scene) {
  const auto& ic = scene.foveal_display.combiner;
  CombinerPrescription c;
  c.mirror_distance_mm = ic.eye_distance_mm;
  const double v = ic.image_distance_mm - ic.eye_distance_mm;
  c.focal_length_mm = v / (ic.magnification - 1.0);
  c.display_distance_mm = v / ic.magnification;
  return c;
}

double diffractionMtf30Cpd(double pupil_diameter_mm, double wavelength_nm) {
  const double cutoff = pupil_diameter_mm / (wavelength_nm * 1e-6) * kDeg;  // cycles per degree
  double lo = 0, hi = cutoff;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (diffractionMtf(mid, cutoff) > 0.3 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

FovealOpticsSample tracedCombinerMtf30(const Scene& scene, double gaze_yaw_deg, double field_deg) {
  const CombinerPrescription c = combinerPrescription(scene);
  const double r_eye = scene.eye.eyeball_diameter_mm / 2;
  const double a = gaze_yaw_deg * kDeg;
  // Zero-gaze pupil at the origin of this local frame, eye centre r behind it.
  const Eigen::Vector3d centre(0, 0, -r_eye);
  const Eigen::Vector3d pupil = centre + r_eye * Eigen::Vector3d(std::sin(a), 0, std::cos(a));
  const Eigen::Vector3d gaze(std::sin(a), 0, std::cos(a));
  const Eigen::Vector3d ex = Eigen::Vector3d::UnitY().cross(gaze).normalized(), ey = Eigen::Vector3d::UnitY();
  const double d_f = scene.foveal_display.combiner.image_distance_mm;
  auto imagePoint = [&](double field) {
    const Eigen::Vector3d dir(std::sin(field * kDeg), 0, std::cos(field * kDeg));
    return Eigen::Vector3d(pupil + (d_f - pupil.z()) / dir.z() * dir);
  };
  const Eigen::Vector3d q = imagePoint(field_deg);
  // Plate scale: display mm per radian of field, from neighbouring chief rays.
  constexpr double h = 0.01;
  const auto c1 = traceCombinerToDisplay(c, pupil, imagePoint(field_deg + h));
  const auto c0 = traceCombinerToDisplay(c, pupil, imagePoint(field_deg - h));
  FovealOpticsSample out;
  out.best_focus_mm = (q - pupil).norm();
  if (!c1 || !c0) return out;
  const double mm_per_rad = std::abs(c1->x() - c0->x()) / (2 * h * kDeg);

  const double rp = scene.eye.pupil_diameter_mm / 2;
  const Eigen::Vector3d field_dir = (q - pupil).normalized();
  // 1-D RMS spread on the display of the rays aimed at the image point at distance `dist`.
  auto spread = [&](double dist) {
    const Eigen::Vector3d target = pupil + dist * field_dir;
    constexpr int n = 16;
    double sx = 0, sxx = 0;
    int count = 0;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const double u = -1 + (2.0 * i + 1) / n, w = -1 + (2.0 * j + 1) / n;
        if (u * u + w * w > 1) continue;
        const auto hit = traceCombinerToDisplay(c, pupil + rp * (u * ex + w * ey), target);
        if (!hit) continue;
        sx += hit->x();
        sxx += hit->x() * hit->x();
        ++count;
      }
    if (count < 3) return std::numeric_limits<double>::infinity();
    const double mean = sx / count;
    return std::sqrt(std::max(0.0, sxx / count - mean * mean));
  };
  if (mm_per_rad <= 0) return out;
  // The eye accommodates to the best focus of this field (the image surface is curved,
  // Fig. S8; the seed notes the change stays within the eye's depth of field): golden-
  // section search of the image distance in dioptres between 0.25x and 4x the nominal.
  const double nominal = (q - pupil).norm();
  double lo = 0.25 / nominal, hi = 4.0 / nominal;  // vergence (1/mm)
  constexpr double kInvPhi = 0.6180339887498949;
  double x1 = hi - kInvPhi * (hi - lo), x2 = lo + kInvPhi * (hi - lo);
  double f1 = spread(1 / x1), f2 = spread(1 / x2);
  for (int it = 0; it < 40; ++it) {
    if (f1 <= f2) {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - kInvPhi * (hi - lo);
      f1 = spread(1 / x1);
    } else {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + kInvPhi * (hi - lo);
      f2 = spread(1 / x2);
    }
  }
  const double best_vergence = f1 <= f2 ? x1 : x2;
  out.best_focus_mm = 1 / best_vergence;
  const double sigma_mm = std::min(f1, f2);
  const double sigma_deg = sigma_mm / mm_per_rad / kDeg;
  out.rms_blur_arcmin = sigma_deg * 60;
  const double cutoff = scene.eye.pupil_diameter_mm / (kWavelengthNm * 1e-6) * kDeg;
  auto mtf = [&](double nu) {
    return diffractionMtf(nu, cutoff) *
           std::exp(-2 * std::numbers::pi * std::numbers::pi * sigma_deg * sigma_deg * nu * nu);
  };
  double nu_lo = 0, nu_hi = cutoff;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (nu_lo + nu_hi);
    (mtf(mid) > 0.3 ? nu_lo : nu_hi) = mid;
  }
  out.mtf30_cpd = 0.5 * (nu_lo + nu_hi);
  return out;
}

}  // namespace fovea

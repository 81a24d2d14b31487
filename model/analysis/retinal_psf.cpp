#include "model/analysis/retinal_psf.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <vector>

#include <Eigen/Dense>
#include <opencv2/core.hpp>

#include "model/analysis/foveal_optics.h"
#include "model/physics/eye_model.h"
#include "model/physics/eye_oblique_focus.h"
#include "model/physics/hologram_astigmatism.h"
#include "model/physics/projector_rays.h"
#include "model/physics/schematic_eye.h"
#include "model/scene/scene_geometry.h"
#include "model/units.h"

namespace fovea {

namespace {

constexpr double kPsfFwhmPerRadius = 1.1774100225154747;  // sqrt(2 ln 2): Gaussian FWHM / 1/e^2 radius
constexpr double kPsfArcminPerRad = 60.0 / kDeg;

// Moves the zero frequency / zero angle to the grid centre (n even: its own inverse).
void psfFftShift(cv::Mat& m) {
  const int cx = m.cols / 2, cy = m.rows / 2;
  cv::Mat q0(m, cv::Rect(0, 0, cx, cy)), q1(m, cv::Rect(cx, 0, cx, cy)), q2(m, cv::Rect(0, cy, cx, cy)),
      q3(m, cv::Rect(cx, cy, cx, cy)), tmp;
  q0.copyTo(tmp);
  q3.copyTo(q0);
  tmp.copyTo(q3);
  q1.copyTo(tmp);
  q2.copyTo(q1);
  tmp.copyTo(q2);
}

double psfSincPi(double x) {
  return std::abs(x) < 1e-12 ? 1.0 : std::sin(kPi * x) / (kPi * x);
}

}  // namespace

SpotMetrics gaussianSpotMetrics(double w_arcmin) {
  SpotMetrics m;
  m.fwhm_arcmin = kPsfFwhmPerRadius * w_arcmin;
  const double sigma_deg = 0.5 * w_arcmin / 60.0;
  auto at = [&](double level) { return std::sqrt(-std::log(level) / 2.0) / (kPi * sigma_deg); };
  m.mtf50_cpd = at(0.5);
  m.mtf10_cpd = at(0.1);
  return m;
}

PeripheralSpot peripheralSpot(const Scene& scene, double wavelength_nm, double accommodation_d,
                              std::array<double, 2> gaze_deg, std::array<double, 2> hoe_shift_mm) {
  PeripheralSpot s;
  s.wavelength_nm = wavelength_nm;
  const EyePlacement eye = placeEye(scene, gaze_deg[0], gaze_deg[1]);
  const Frame plate = frameOf(scene.hoe.pose);
  const double denom = eye.gaze.dot(plate.z());
  if (std::abs(denom) < 1e-12) return s;
  // A lateral shift keeps the plate's plane.
  const double t = (plate.origin - eye.pupil_center).dot(plate.z()) / denom;
  if (t <= 0) return s;
  return peripheralSpotAt(scene, wavelength_nm, accommodation_d, gaze_deg, hoe_shift_mm,
                          eye.pupil_center + t * eye.gaze);
}

PeripheralSpot peripheralSpotAt(const Scene& scene, double wavelength_nm, double accommodation_d,
                                std::array<double, 2> gaze_deg, std::array<double, 2> hoe_shift_mm,
                                const Eigen::Vector3d& hit) {
  PeripheralSpot s;
  s.wavelength_nm = wavelength_nm;
  const EyePlacement eye = placeEye(scene, gaze_deg[0], gaze_deg[1]);
  const Eigen::Matrix3d eye_axes = rotationFromDeg({gaze_deg[0], gaze_deg[1], 0.0});
  const Frame plate = frameOf(scene.hoe.pose);
  const Eigen::Vector3d shift = plate.x() * hoe_shift_mm[0] + plate.y() * hoe_shift_mm[1];
  const Eigen::Vector3d local = plate.toLocal(hit - shift);
  if (std::abs(local.x()) > 0.5 * scene.hoe.size_mm[0] || std::abs(local.y()) > 0.5 * scene.hoe.size_mm[1]) return s;
  if (scene.hoe_layers.empty()) return s;
  // The layer recorded nearest the laser carries it (the others are far off Bragg).
  std::size_t best = 0;
  for (std::size_t i = 1; i < scene.hoe_layers.size(); ++i)
    if (std::abs(scene.hoe_layers[i].recording.wavelength_nm - wavelength_nm) <
        std::abs(scene.hoe_layers[best].recording.wavelength_nm - wavelength_nm))
      best = i;
  const HoeRecording& rec = scene.hoe_layers[best].recording;
  HologramPointGeometry g;
  g.plate_x = plate.x();
  g.plate_y = plate.y();
  g.point = hit - shift;  // the fringes at `hit` were recorded here
  g.reference_mm = toVec(rec.reference_point_mm);
  g.signal_mm = toVec(rec.signal_point_mm);
  g.mu = wavelength_nm / rec.wavelength_nm;
  const double lr = (g.point - g.reference_mm).norm();
  const double ls = (g.point - g.signal_mm).norm();
  const double phi = (1.0 / lr + 1.0 / ls) * g.mu;  // 1/mm: the sagittal power
  s.layer = static_cast<int>(best);
  s.hoe_power_d = phi * 1000.0;
  const Eigen::Vector3d src = projectorSource(scene.projector, 0.0);
  s.throw_mm = (hit - src).norm();
  const Eigen::Vector3d u_in = (hit - src).normalized();
  const Eigen::Vector3d u_out = hologramOutDirection(g, u_in, eye.pupil_center - hit);
  if (u_out.isZero()) return s;
  // To the pupil plane (normal to the gaze through the pupil centre) along the ray.
  const double along = u_out.dot(-eye.gaze);
  if (!(along > 1e-9)) return s;
  const double t = (hit - eye.pupil_center).dot(eye.gaze) / along;
  if (!(t > 0)) return s;
  s.hoe_to_pupil_mm = t;
  s.field_deg = fieldAngleDeg(eye_axes, u_out);

  const PixelBeamModel& pb = scene.projector.pixel_beam;
  const double lambda_mm = wavelength_nm * 1e-6;
  const double w0 = pb.waist_fwhm_um * 1e-3 / kPsfFwhmPerRadius;
  const double theta = pb.divergence_mrad * 1e-3 / kPsfFwhmPerRadius;
  double lambda_eff = kPi * w0 * theta;
  double z_r = theta > 0 ? w0 / theta : 1e12;
  if (lambda_eff < lambda_mm) {  // below the diffraction limit: a true Gaussian of that waist
    lambda_eff = lambda_mm;
    z_r = kPi * w0 * w0 / lambda_mm;
  }
  s.lambda_eff_nm = lambda_eff * 1e6;
  std::complex<double> q(s.throw_mm - pb.waist_distance_mm, z_r);
  // The beam-shaping lens (A.2), when the scene enables it, as an ideal thin lens where the
  // chief ray passes its plane's foot point: q is propagated back to the lens, through it and on
  // to the plate (the real thick lens and its obliquity are beam_shaping.h's business).
  if (scene.lens.enabled && scene.lens.focal_length_mm != 0) {
    const double d1 = (toVec(scene.lens.pose.position_mm) - src).dot(u_in);
    if (d1 > 0 && d1 < s.throw_mm) {
      std::complex<double> ql(d1 - pb.waist_distance_mm, z_r);
      ql = transformQ(thinLens(1.0 / scene.lens.focal_length_mm), ql);
      q = transformQ(freeSpace(s.throw_mm - d1), ql);
      s.through_lens = true;
    }
  }
  s.beam_radius_hoe_mm = gaussianRadiusMm(q, lambda_eff);
  // The HOE (hologram_astigmatism.h): the outgoing beam's complex curvature matrix in the
  // field's (yaw, pitch) basis normal to the ray (the eye frame's tangent directions at the
  // ray's field angle); its real part's eigenvalues are the two vergences after the plate.
  const double yaw = s.field_deg[0] * kDeg, pitch = s.field_deg[1] * kDeg;
  Eigen::Matrix<double, 3, 2> basis;
  basis.col(0) = eye_axes * Eigen::Vector3d(std::cos(yaw), 0.0, -std::sin(yaw));
  basis.col(1) =
      eye_axes * Eigen::Vector3d(-std::sin(pitch) * std::sin(yaw), std::cos(pitch), -std::sin(pitch) * std::cos(yaw));
  const Eigen::Matrix2cd m = hologramOutputCurvature(g, u_in, q, u_out, basis);
  {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> re(0.5 * (m.real() + m.real().transpose()));
    s.vergence_d = {re.eigenvalues()[0] * 1000.0, re.eigenvalues()[1] * 1000.0};
    s.astigmatism_d = std::abs(s.vergence_d[1] - s.vergence_d[0]);
  }
  // Through free space and the eye: Q -> (A Q + B)(C Q + D)^-1, scalar ABCD (rotationally
  // symmetric, reduced: air before the pupil), Q = M^-1 (Arnaud's astigmatic Gaussian beams,
  // Siegman ch. 20); the intensity exp(-x^T Sigma^-1 x / 2) has Sigma^-1 = -2 k Im(Q^-1).
  using C2 = Eigen::Matrix2cd;
  const C2 id = C2::Identity();
  auto through = [&](const RayMatrix& r, const C2& qm) -> C2 {
    return (r.A * qm + r.B * id) * (r.C * qm + r.D * id).inverse();
  };
  const double k_eff = 2.0 * kPi / lambda_eff;
  auto covariance = [&](const C2& qm) -> Eigen::Matrix2d {
    const Eigen::Matrix2d im = qm.inverse().imag();
    return (-2.0 * k_eff * 0.5 * (im + im.transpose())).inverse();
  };
  auto meanRadius = [](const Eigen::Matrix2d& cov) { return 2.0 * std::pow(cov.determinant(), 0.25); };
  C2 qm = m.inverse();
  qm = through(freeSpace(t), qm);
  const Eigen::Matrix2d cov_pupil = covariance(qm);
  s.beam_radius_pupil_mm = meanRadius(cov_pupil);
  const double a = 0.5 * scene.eye.pupil_diameter_mm;
  s.pupil_transmission = 1.0 - std::exp(-2.0 * a * a / (s.beam_radius_pupil_mm * s.beam_radius_pupil_mm));
  const SchematicEyeState e = navarroEye(accommodation_d, wavelength_nm);
  // The eye off its axis (eye_oblique_focus.h): at the ray's angle theta from the line of sight,
  // entering the pupil h from its centre, the real eye focuses the beam's pencil with an extra
  // power P over its paraxial matrix; it acts as a thin astigmatic lens at the entrance pupil,
  // Q^-1 -> Q^-1 - P, with P = P_mm m m^T + P_ss s s^T + P_ms (m s^T + s m^T) in the field's
  // (yaw, pitch) basis: m the meridional direction normal to the ray (towards the side it travels
  // to), s across it. The pupil centre stands for the chief ray's crossing (the scene's pupil is
  // the paraxial entrance pupil). Beyond 60 deg the 60 deg values; offsets beyond 4 mm, 4 mm.
  {
    const double cos_theta = std::clamp(-u_out.dot(eye.gaze), -1.0, 1.0);
    s.eye_field_deg = std::acos(cos_theta) / kDeg;
    const Eigen::Vector3d offset = hit + t * u_out - eye.pupil_center;  // in the pupil plane
    // The meridional direction in the pupil plane: where the ray travels; on the axis, the offset's.
    Eigen::Vector3d lateral = u_out + cos_theta * eye.gaze;
    if (lateral.norm() < 1e-9) lateral = offset;
    if (lateral.norm() > 1e-12) {
      const Eigen::Vector3d m_pupil = lateral.normalized();
      const Eigen::Vector3d s_dir = eye.gaze.cross(m_pupil).normalized();  // across, normal to the ray too
      double h_m = offset.dot(m_pupil), h_s = offset.dot(s_dir);
      const double rho = std::hypot(h_m, h_s);
      if (rho > kMaxPupilOffsetMm) {  // onto the limit, a hair inside so rounding cannot cross it
        const double scale = kMaxPupilOffsetMm / rho * (1.0 - 1e-12);
        h_m *= scale;
        h_s *= scale;
      }
      s.pupil_offset_mm = {h_m, h_s};
      const EyePencilPower ep = eyePencilPower(e, std::min(s.eye_field_deg, 60.0), h_m, h_s);
      if (ep.valid) {
        s.eye_power_d = {ep.meridional_d, ep.sagittal_d};
        s.eye_power_cross_d = ep.cross_d;
        const Eigen::Vector3d m_ray = (m_pupil - m_pupil.dot(u_out) * u_out).normalized();
        const Eigen::Vector2d mt(m_ray.dot(basis.col(0)), m_ray.dot(basis.col(1)));
        const Eigen::Vector2d st(s_dir.dot(basis.col(0)), s_dir.dot(basis.col(1)));
        const Eigen::Matrix2d p = (ep.meridional_d * mt * mt.transpose() + ep.sagittal_d * st * st.transpose() +
                                   ep.cross_d * (mt * st.transpose() + st * mt.transpose())) /
                                  1000.0;
        qm = (qm.inverse() - p.cast<std::complex<double>>()).inverse();
      }
    }
  }
  qm = through(e.pupil_to_retina, qm);
  const Eigen::Matrix2d cov_retina = covariance(qm);
  s.beam_radius_retina_mm = meanRadius(cov_retina);
  // As visual angle (arcmin^2): the retina's mm per radian of the chief ray.
  const double scale = kPsfArcminPerRad / e.retina_mm_per_rad;
  const Eigen::Matrix2d cov = cov_retina * scale * scale;
  s.covariance_arcmin2 = {cov(0, 0), cov(1, 1), cov(0, 1)};
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(cov);
  s.radius_minor_arcmin = 2.0 * std::sqrt(std::max(0.0, es.eigenvalues()[0]));
  s.radius_major_arcmin = 2.0 * std::sqrt(std::max(0.0, es.eigenvalues()[1]));
  s.orientation_deg = std::atan2(es.eigenvectors()(1, 1), es.eigenvectors()(0, 1)) / kDeg;
  if (s.orientation_deg > 90) s.orientation_deg -= 180;
  if (s.orientation_deg <= -90) s.orientation_deg += 180;
  s.radius_1e2_arcmin = std::sqrt(s.radius_major_arcmin * s.radius_minor_arcmin);
  s.metrics = gaussianSpotMetrics(s.radius_1e2_arcmin);
  s.metrics_major = gaussianSpotMetrics(s.radius_major_arcmin);
  s.valid = true;
  return s;
}

PupilPsf defocusedPupilPsf(double pupil_diameter_mm, double wavelength_nm, double defocus_d, int grid) {
  if (!(pupil_diameter_mm > 0) || !(wavelength_nm > 0) || !std::isfinite(defocus_d))
    throw std::invalid_argument("pupil PSF: pupil and wavelength must be positive, defocus finite");
  const double lambda = wavelength_nm * 1e-6, d = pupil_diameter_mm, e = defocus_d / 1000.0;
  // Field lambda/dx = lambda N_p / D must hold the geometric disc (|E| D rad) three times over
  // plus 40 diffraction units; the defocus phase pi E r^2 / lambda then changes by at most
  // pi E D^2/(lambda N_p) <= pi/1.5 per pupil sample. At least 128 samples across the pupil
  // (angular pixel lambda/(8 D) at the 1024 grid).
  const double blur_units = std::abs(e) * d * d / lambda;  // geometric diameter in lambda/D
  int np = std::max(128, static_cast<int>(std::ceil(3.0 * blur_units + 40.0)));
  int n = grid;
  while (np > n / 2 && n < 2048) n *= 2;
  np = std::min(np, n / 2);
  const double dx = d / np;
  // The pupil sits in the grid's first rows (centre m, m): a shift only multiplies the
  // spectrum by a linear phase, so |FFT|^2 is that of the centred pupil (Goodman, ch. 2, the
  // shift theorem), and cv::dft skips the row transforms of the empty rows (nonzeroRows).
  const int m = np / 2 + 2, rows = 2 * m + 1;
  cv::Mat field(n, n, CV_64FC2, cv::Scalar(0, 0));
  const double a = 0.5 * d;
  constexpr int kSub = 4;
  for (int iy = 0; iy < rows; ++iy) {
    auto* row = field.ptr<cv::Vec2d>(iy);
    for (int ix = 0; ix < rows; ++ix) {
      const double x = (ix - m) * dx, y = (iy - m) * dx, r = std::hypot(x, y);
      double cover = 0;
      if (r < a - dx) {
        cover = 1;
      } else if (r < a + dx) {  // anti-aliased edge: sub-sampled coverage
        int in = 0;
        for (int sy = 0; sy < kSub; ++sy)
          for (int sx = 0; sx < kSub; ++sx)
            in += std::hypot(x + ((sx + 0.5) / kSub - 0.5) * dx, y + ((sy + 0.5) / kSub - 0.5) * dx) <= a;
        cover = static_cast<double>(in) / (kSub * kSub);
      }
      if (cover == 0) continue;
      const double phase = kPi * e * r * r / lambda;  // k W, W = E r^2 / 2
      row[ix] = cv::Vec2d(cover * std::cos(phase), cover * std::sin(phase));
    }
  }
  cv::dft(field, field, 0, rows);
  cv::Mat psf(n, n, CV_64F);
  for (int y = 0; y < n; ++y) {
    const auto* in = field.ptr<cv::Vec2d>(y);
    double* out = psf.ptr<double>(y);
    for (int x = 0; x < n; ++x) out[x] = in[x][0] * in[x][0] + in[x][1] * in[x][1];
  }
  psfFftShift(psf);  // zero angle to the grid centre
  psf /= cv::sum(psf)[0];
  PupilPsf out;
  out.psf = psf;
  out.sample_arcmin = lambda / (n * dx) * kPsfArcminPerRad;
  out.pupil_diameter_mm = d;
  out.wavelength_nm = wavelength_nm;
  out.defocus_d = defocus_d;
  return out;
}

double psfFwhmArcmin(const cv::Mat& psf, double sample) {
  const int c = psf.cols / 2, r = psf.rows / 2;
  const double* row = psf.ptr<double>(r);
  double peak = 0;
  for (int i = 0; i < psf.cols; ++i) peak = std::max(peak, row[i]);
  const double half = 0.5 * peak;
  auto outer = [&](int dir) {  // outermost crossing of half maximum on one side
    int last = 0;
    for (int k = 0; c + dir * k >= 0 && c + dir * k < psf.cols; ++k)
      if (row[c + dir * k] >= half) last = k;
    const int k1 = last + 1;
    if (c + dir * k1 < 0 || c + dir * k1 >= psf.cols) return static_cast<double>(last);
    const double v0 = row[c + dir * last], v1 = row[c + dir * k1];
    return last + (v0 - half) / (v0 - v1);
  };
  return (outer(1) + outer(-1)) * sample;
}

double spotWidthArcmin(const cv::Mat& psf, double sample_arcmin) {
  return 2.0 * encircledEnergyRadiusArcmin(psf, sample_arcmin, 0.5);
}

double encircledEnergyRadiusArcmin(const cv::Mat& psf, double sample, double fraction) {
  // Radial histogram of the power in bins of 1/8 sample (O(N), no sort), cumulated, and the
  // crossing interpolated linearly inside its bin.
  const int c = psf.cols / 2, cy = psf.rows / 2;
  constexpr double kBinsPerSample = 8.0;
  const double r_max = std::hypot(psf.cols, psf.rows);
  std::vector<double> hist(static_cast<std::size_t>(r_max * kBinsPerSample) + 2, 0.0);
  double total = 0;
  for (int y = 0; y < psf.rows; ++y) {
    const double* row = psf.ptr<double>(y);
    const double dy2 = static_cast<double>(y - cy) * (y - cy);
    for (int x = 0; x < psf.cols; ++x) {
      if (row[x] == 0) continue;
      hist[static_cast<std::size_t>(std::sqrt((x - c) * (x - c) + dy2) * kBinsPerSample)] += row[x];
      total += row[x];
    }
  }
  const double goal = fraction * total;
  double acc = 0;
  for (std::size_t i = 0; i < hist.size(); ++i) {
    if (acc + hist[i] >= goal && hist[i] > 0)
      return (static_cast<double>(i) + (goal - acc) / hist[i]) / kBinsPerSample * sample;
    acc += hist[i];
  }
  return static_cast<double>(hist.size()) / kBinsPerSample * sample;
}

double firstMinimumArcmin(const cv::Mat& psf, double sample) {
  // The Airy zero is a simple zero of the amplitude: |amplitude| = sqrt(intensity) is V-shaped
  // there, so the root is found by linear interpolation of the signed amplitude between the
  // smallest sample and its smaller neighbour (a parabola through the intensity would be
  // biased by the lobes' asymmetry).
  const int c = psf.cols / 2;
  const double* row = psf.ptr<double>(psf.rows / 2);
  for (int k = 1; c + k + 1 < psf.cols; ++k) {
    const double a = row[c + k - 1], b = row[c + k], d = row[c + k + 1];
    if (b <= a && b <= d) {
      const double sa = std::sqrt(a), sb = std::sqrt(b), sd = std::sqrt(d);
      const double off = sd < sa ? sb / (sb + sd) : -sb / (sb + sa);
      return (k + off) * sample;
    }
  }
  return 0;
}

double MtfCurve::frequencyAt(double level) const {
  for (std::size_t i = 1; i < mtf.size(); ++i)
    if (mtf[i] < level && mtf[i - 1] >= level)
      return cpd[i - 1] + (mtf[i - 1] - level) / (mtf[i - 1] - mtf[i]) * (cpd[i] - cpd[i - 1]);
  return 0;
}

namespace {

// OTF of a centred real PSF grid (complex, zero frequency at (0,0)): a real-input DFT.
cv::Mat psfOtf(const cv::Mat& psf) {
  cv::Mat f = psf.clone(), otf;
  psfFftShift(f);
  cv::dft(f, otf, cv::DFT_COMPLEX_OUTPUT);
  return otf;
}

// Multiplies an OTF by the pixel box sinc(p fx) sinc(p fy) and the Gaussian blur
// exp(-2 pi^2 sigma^2 (fx^2 + fy^2)); both separable, so one 1-D factor per axis.
void psfApplyFactors(cv::Mat& otf, double df_cpd, double pixel_deg, double sigma_arcmin) {
  if (pixel_deg == 0 && sigma_arcmin == 0) return;
  const int n = otf.cols;
  const double sigma_deg = sigma_arcmin / 60.0;
  std::vector<double> g(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    const double f = (k <= n / 2 ? k : k - n) * df_cpd;
    g[static_cast<std::size_t>(k)] =
        psfSincPi(pixel_deg * f) * std::exp(-2.0 * kPi * kPi * sigma_deg * sigma_deg * f * f);
  }
  for (int y = 0; y < otf.rows; ++y) {
    auto* row = otf.ptr<cv::Vec2d>(y);
    const double gy = g[static_cast<std::size_t>(y)];
    for (int x = 0; x < n; ++x) row[x] *= gy * g[static_cast<std::size_t>(x)];
  }
}

// |OTF| along +fx, normalised at zero frequency.
MtfCurve psfMtfRow(const cv::Mat& otf, double df_cpd) {
  const cv::Vec2d* row = otf.ptr<cv::Vec2d>(0);
  const double dc = std::hypot(row[0][0], row[0][1]);
  MtfCurve m;
  for (int k = 0; k <= otf.cols / 2; ++k) {
    m.cpd.push_back(k * df_cpd);
    m.mtf.push_back(std::hypot(row[k][0], row[k][1]) / dc);
  }
  return m;
}

// The eye's part of a foveal spot, which depends on the pupil, the wavelength and the defocus
// only (not on the gaze): its OTF and metrics, kept for the last few requests (about 16 MB
// each at the 1024 grid; at most kPsfCacheBytes in all) so that a new gaze recomputes only the
// combiner's blur factor.
struct EyePsfEntry {
  double pupil_mm = 0, wavelength_nm = 0, defocus_d = 0;
  cv::Mat otf;
  double sample_arcmin = 0;
  SpotMetrics eye_only;
  double eye_profile_fwhm_arcmin = 0;
};
constexpr std::size_t kPsfCacheBytes = 160u << 20;

std::shared_ptr<const EyePsfEntry> eyePsf(double pupil_mm, double wavelength_nm, double defocus_d) {
  static std::mutex mutex;
  static std::deque<std::shared_ptr<const EyePsfEntry>> cache;  // most recent first
  {
    const std::lock_guard<std::mutex> lock(mutex);
    for (auto it = cache.begin(); it != cache.end(); ++it)
      if ((*it)->pupil_mm == pupil_mm && (*it)->wavelength_nm == wavelength_nm && (*it)->defocus_d == defocus_d) {
        auto hit = *it;
        cache.erase(it);
        cache.push_front(hit);
        return hit;
      }
  }
  auto e = std::make_shared<EyePsfEntry>();
  e->pupil_mm = pupil_mm;
  e->wavelength_nm = wavelength_nm;
  e->defocus_d = defocus_d;
  const PupilPsf p = defocusedPupilPsf(pupil_mm, wavelength_nm, defocus_d);
  e->sample_arcmin = p.sample_arcmin;
  e->otf = psfOtf(p.psf);
  const MtfCurve eye_mtf = psfMtfRow(e->otf, 60.0 / (p.psf.cols * p.sample_arcmin));
  e->eye_only = {spotWidthArcmin(p.psf, p.sample_arcmin), eye_mtf.frequencyAt(0.5), eye_mtf.frequencyAt(0.1)};
  e->eye_profile_fwhm_arcmin = psfFwhmArcmin(p.psf, p.sample_arcmin);
  const std::lock_guard<std::mutex> lock(mutex);
  cache.push_front(e);
  std::size_t bytes = 0;
  for (std::size_t i = 0; i < cache.size(); ++i) {
    bytes += cache[i]->otf.total() * cache[i]->otf.elemSize();
    if (bytes > kPsfCacheBytes && i >= 3) {  // keep at least one accommodation's three primaries
      cache.resize(i);
      break;
    }
  }
  return e;
}

}  // namespace

MtfCurve mtfFromPsf(const cv::Mat& psf, double sample_arcmin, double pixel_deg, double sigma_arcmin) {
  cv::Mat otf = psfOtf(psf);
  const double df_cpd = 60.0 / (psf.cols * sample_arcmin);
  psfApplyFactors(otf, df_cpd, pixel_deg, sigma_arcmin);
  return psfMtfRow(otf, df_cpd);
}

FovealSpot fovealSpot(const Scene& scene, double wavelength_nm, double accommodation_d, std::array<double, 2> gaze_deg,
                      std::optional<double> pupil_diameter_mm) {
  FovealSpot s;
  s.wavelength_nm = wavelength_nm;
  const double pupil = pupil_diameter_mm.value_or(scene.eye.pupil_diameter_mm);
  const SchematicEyeState eye = navarroEye(accommodation_d, wavelength_nm);
  const double d_f = scene.foveal_display.combiner.image_distance_mm;
  s.defocus_d = defocusD(eye, -1000.0 / d_f);
  s.geometric_blur_arcmin = std::abs(s.defocus_d) / 1000.0 * pupil * kPsfArcminPerRad;
  s.pixel_arcmin = fovealFovDeg(scene)[0] / scene.foveal_display.pixels[0] * 60.0;
  s.combiner_rms_arcmin = tracedCombinerMtf30(scene, gaze_deg[0], gaze_deg[0]).rms_blur_arcmin;
  const auto eye_psf = eyePsf(pupil, wavelength_nm, s.defocus_d);
  s.sample_arcmin = eye_psf->sample_arcmin;
  s.eye_only = eye_psf->eye_only;
  s.eye_profile_fwhm_arcmin = eye_psf->eye_profile_fwhm_arcmin;
  const double df_cpd = 60.0 / (eye_psf->otf.cols * s.sample_arcmin);
  cv::Mat otf = eye_psf->otf.clone(), back;
  psfApplyFactors(otf, df_cpd, s.pixel_arcmin / 60.0, s.combiner_rms_arcmin);
  const MtfCurve total = psfMtfRow(otf, df_cpd);
  cv::dft(otf, back, cv::DFT_INVERSE | cv::DFT_REAL_OUTPUT | cv::DFT_SCALE);
  psfFftShift(back);
  back = cv::max(back, 0.0);
  back /= cv::sum(back)[0];
  s.psf = back;
  s.metrics = {spotWidthArcmin(back, s.sample_arcmin), total.frequencyAt(0.5), total.frequencyAt(0.1)};
  s.profile_fwhm_arcmin = psfFwhmArcmin(back, s.sample_arcmin);
  return s;
}

}  // namespace fovea

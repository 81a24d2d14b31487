// Retinal image of both displays (issue 29): the schematic eye, the peripheral Gaussian-beam
// PSF, the foveal pupil PSF, speckle and energy, each against a closed form.
#include <QtTest>

#include <cmath>
#include <complex>

#include "app/embedded_scene.h"
#include "model/analysis/foveal_optics.h"
#include "model/analysis/retinal_psf.h"
#include "model/image/foveation.h"
#include "model/image/retina_image.h"
#include "model/image/speckle_grain.h"
#include "model/image/test_target.h"
#include "model/physics/eye_oblique_focus.h"
#include "model/physics/hologram_astigmatism.h"
#include "model/physics/lateral_colour.h"
#include "model/physics/schematic_eye.h"
#include "model/scene/scene_geometry.h"
#include "model/scene/scene_io.h"
#include "model/units.h"

namespace tst_retinal_psf {

using namespace fovea;

namespace {
using fovea::embeddedDefaultScene;
constexpr double kArcmin = 60.0 / kDeg;  // arcmin per radian

// The prototype with lasers 10 nm off their layers' recording wavelengths (red, blue) and the
// green one on it: the three layers are identical except for their wavelength.
Scene offsetLasers() {
  Scene s = embeddedDefaultScene();
  s.projector.wavelengths_nm = {650.0, 532.0, 450.0};
  return s;
}

// Closed form (lateral_colour.h): the calibration laser (on its layer's wavelength) reaches
// the pupil centre S at yaw theta from plate point P = S + (d / cos theta)(sin theta, 0, cos theta)
// (plate at z = 0, S at (0, 0, -d)); there a laser mu = lambda/lambda_rec leaves along
// out_x = (1 - mu) r_x + mu s_x with s_x = -sin theta and r = (P - R)/|P - R| (R the
// reference point = the projector, both in the horizontal plane), so it is seen at
// yaw = asin(-out_x). Returns that yaw in degrees.
double grating_yaw_deg(double theta_deg, double mu, const Vec3mm& reference_mm, double relief_mm) {
  const double th = theta_deg * kDeg;
  const double px = relief_mm * std::tan(th);
  const double rx = px - reference_mm[0], rz = 0.0 - reference_mm[2];
  const double r_x = rx / std::hypot(rx, rz);
  const double out_x = (1 - mu) * r_x - mu * std::sin(th);
  return std::asin(-out_x) / kDeg;
}

// Centroid (yaw, pitch in degrees, world) of channel k of a retinal image over a window.
std::array<double, 2> channelCentroidDeg(const cv::Mat& img, const image::DisplayAngles& ang, int k, double yaw_lo,
                                         double yaw_hi) {
  double sw = 0, sx = 0, sy = 0;
  for (int y = 0; y < img.rows; ++y)
    for (int x = 0; x < img.cols; ++x) {
      const double yaw = ((x + 0.5) / img.cols - 0.5) * ang.peripheral_fov_deg[0];
      if (yaw < yaw_lo || yaw > yaw_hi) continue;
      const double pitch = (0.5 - (y + 0.5) / img.rows) * ang.peripheral_fov_deg[1];
      const double v = img.at<cv::Vec3f>(y, x)[k];
      sw += v;
      sx += v * yaw;
      sy += v * pitch;
    }
  return {sx / sw, sy / sw};
}

// A white Gaussian blob (sigma_deg) at world yaw yaw_deg on the horizon, on the preview's grid.
cv::Mat blobTarget(const image::DisplayAngles& ang, cv::Size size, double yaw_deg, double sigma_deg) {
  cv::Mat t(size, CV_32FC3, cv::Scalar(0, 0, 0));
  for (int y = 0; y < size.height; ++y)
    for (int x = 0; x < size.width; ++x) {
      const double yaw = ((x + 0.5) / size.width - 0.5) * ang.peripheral_fov_deg[0];
      const double pitch = (0.5 - (y + 0.5) / size.height) * ang.peripheral_fov_deg[1];
      const float v = static_cast<float>(
          std::exp(-0.5 * ((yaw - yaw_deg) * (yaw - yaw_deg) + pitch * pitch) / (sigma_deg * sigma_deg)));
      t.at<cv::Vec3f>(y, x) = cv::Vec3f(v, v, v);
    }
  return t;
}

// A white blob at world yaw `theta_deg` rendered twice on the retina: with one calibration for
// all lasers (common) and with each laser warped on its own (own).
struct BlobRenders {
  image::DisplayAngles ang;
  image::RetinaImageResult common, own;
};
BlobRenders blobRenders(const Scene& s, double theta_deg) {
  BlobRenders r;
  r.ang = image::displayAngles(s);
  const cv::Size size(960,
                      static_cast<int>(std::lround(960 * r.ang.peripheral_fov_deg[1] / r.ang.peripheral_fov_deg[0])));
  const cv::Mat target = blobTarget(r.ang, size, theta_deg, 1.0);
  image::RetinaImageOptions o;
  o.rays = 40000;
  r.common = image::renderRetinaImage(s, target, o);
  o.per_laser_calibration = true;
  r.own = image::renderRetinaImage(s, target, o);
  return r;
}
}  // namespace

class TestRetinalPsf : public QObject {
  Q_OBJECT
 private slots:
  void gaussianBeamThroughThinLensEye() {
    // Reduced thin-lens eye: power P at the pupil, vitreous index n, length L. A beam with its
    // waist w0 at the lens has, at depth z in the medium (wavelength lambda/n, image-side focal
    // length f' = n/P), w(z)^2 = w0^2 [(1 - z/f')^2 + (z/z_R)^2], z_R = n pi w0^2 / lambda
    // (Siegman, Lasers, ch. 17/20). The ABCD chain must agree.
    const double lambda = 532e-6, n = 1.336, p = 0.060;
    for (double w0 : {0.05, 0.3, 1.0})
      for (double z : {5.0, 17.0, 22.27, 30.0}) {
        const double zr = kPi * w0 * w0 / lambda;
        const std::complex<double> q(0.0, zr);  // waist at the lens, in air
        const std::complex<double> out = transformQ(freeSpace(z, n) * thinLens(p), q);
        const double w_abcd = gaussianRadiusMm(out, lambda);
        const double f = n / p, zrm = n * kPi * w0 * w0 / lambda;
        const double w_closed = w0 * std::sqrt(std::pow(1 - z / f, 2) + std::pow(z / zrm, 2));
        QVERIFY2(std::abs(w_abcd / w_closed - 1) < 0.01,
                 qPrintable(QString("w0 %1 z %2: %3 vs %4").arg(w0).arg(z).arg(w_abcd).arg(w_closed)));
      }
  }

  void navarroEyeIsAPlausibleEye() {
    const SchematicEyeState relaxed = navarroEye(0.0);
    qInfo("Navarro relaxed: power %.2f D, entrance pupil %.3f mm, axial %.3f mm, %.4f mm/rad", relaxed.power_d,
          relaxed.entrance_pupil_mm, relaxed.axial_length_mm, relaxed.retina_mm_per_rad);
    QVERIFY(relaxed.power_d > 58 && relaxed.power_d < 62);  // Navarro 1985: 60.4 D
    QVERIFY(relaxed.entrance_pupil_mm > 2.8 && relaxed.entrance_pupil_mm < 3.3);
    QVERIFY(relaxed.axial_length_mm > 23.8 && relaxed.axial_length_mm < 24.2);
    // docs/physics.md prints 60.39 D, 3.042 mm, 24.012 mm and 16.558 mm/rad: held to those digits.
    QVERIFY(std::abs(relaxed.power_d - 60.39) < 5e-3);
    QVERIFY(std::abs(relaxed.entrance_pupil_mm - 3.042) < 5e-4);
    QVERIFY(std::abs(relaxed.axial_length_mm - 24.012) < 5e-4);
    QVERIFY(std::abs(relaxed.retina_mm_per_rad - 16.558) < 5e-4);
    QCOMPARE(relaxed.pupil_to_retina.A + 1.0, 1.0);  // emmetropic by construction
    for (double d : {0.4, 1.25, 2.0, 3.3, 4.0}) {
      const SchematicEyeState e = navarroEye(d);
      // In focus: rays of vergence -d at the pupil, (y, d y/1000), meet at y = 0 on the retina.
      QVERIFY(std::abs(e.pupil_to_retina.A + e.pupil_to_retina.B * d / 1000.0) < 1e-9);
      QVERIFY(e.power_d > relaxed.power_d);
      QVERIFY(std::abs(e.lens_parameter_d - d) < 0.3 * d + 0.05);
    }
    // Chromatic difference of refraction 460..660 nm (Thibos 1992: ~1.2 D).
    const double lca = chromaticRefractionD(660) - chromaticRefractionD(460);
    QVERIFY(lca > 1.1 && lca < 1.4);
    QVERIFY(std::abs(lca - 1.2) < 0.05);  // docs/physics.md: Rx(660) - Rx(460) = 1.2 D
  }

  void airyFirstZeroAndFwhmInFocus() {
    for (double wl : {460.0, 550.0, 660.0}) {
      const PupilPsf p = defocusedPupilPsf(5.0, wl, 0.0);
      const double unit = wl * 1e-6 / 5.0 * kArcmin;  // lambda/D in arcmin
      const double zero = firstMinimumArcmin(p.psf, p.sample_arcmin);
      const double fwhm = psfFwhmArcmin(p.psf, p.sample_arcmin);
      qInfo("%g nm: first zero %.4f lambda/D (1.2197), FWHM %.4f lambda/D (1.0290)", wl, zero / unit, fwhm / unit);
      QVERIFY(std::abs(zero / (1.2197 * unit) - 1) < 0.01);
      QVERIFY(std::abs(fwhm / (1.0290 * unit) - 1) < 0.01);
      // docs/physics.md prints 1.2230 and 1.0300 lambda/D: held to those digits.
      QVERIFY(std::abs(zero / unit - 1.2230) < 5e-5);
      QVERIFY(std::abs(fwhm / unit - 1.0300) < 5e-5);
    }
  }

  void defocusFollowsGeometricBlur() {
    // Large defocus: the PSF tends to the uniform disc of angular diameter D |dD| (ray optics:
    // the ray at pupil radius r leaves at angle dD r); a fraction f of its power lies within
    // sqrt(f) of its radius. The approach is as the Fresnel number of the defocus grows.
    double last_error = 1;
    for (double dd : {1.0, 2.0, 4.0, 6.0}) {
      const PupilPsf p = defocusedPupilPsf(5.0, 550.0, dd);
      const double radius = 0.5 * 5.0 * dd * 1e-3 * kArcmin;
      const double ee80 = encircledEnergyRadiusArcmin(p.psf, p.sample_arcmin, 0.8);
      const double ee50 = spotWidthArcmin(p.psf, p.sample_arcmin);
      const double err = ee80 / (std::sqrt(0.8) * radius) - 1;
      qInfo(
          "defocus %g D (%.1f waves): EE80 radius %.3f arcmin vs geometric %.3f (%+.2f %%); EE50 diameter %.2f vs %.2f",
          dd, dd * 1e-3 * 6.25 / 2 / 550e-6, ee80, std::sqrt(0.8) * radius, 100 * err, ee50,
          std::sqrt(0.5) * 2 * radius);
      if (dd >= 4.0) QVERIFY(std::abs(err) < 0.03);
      // docs/physics.md prints -4.4, -3.0, -1.4 and -0.5 %: held to those digits.
      const double printed = dd == 1.0 ? -4.4 : dd == 2.0 ? -3.0 : dd == 4.0 ? -1.4 : -0.5;
      QVERIFY(std::abs(100 * err - printed) < 0.05);
      QVERIFY(std::abs(err) <= last_error + 1e-3);
      last_error = std::abs(err);
    }
    // Small defocus (0.02 D: 0.11 wave peak to valley at 550 nm): still the Airy widths (FWHM
    // 1.029 lambda/D; EE50 diameter 1.0697 lambda/D, where 1 - J0^2 - J1^2 = 1/2).
    const PupilPsf small = defocusedPupilPsf(5.0, 550.0, 0.02);
    const double unit = 550e-6 / 5.0 * kArcmin;
    QVERIFY(std::abs(psfFwhmArcmin(small.psf, small.sample_arcmin) / (1.029 * unit) - 1) < 0.02);
    qInfo("0.02 D: EE50 diameter %.4f lambda/D", spotWidthArcmin(small.psf, small.sample_arcmin) / unit);
    QVERIFY(std::abs(spotWidthArcmin(small.psf, small.sample_arcmin) / (1.0697 * unit) - 1) < 0.015);
  }

  void mtfOfAGaussianGrid() {
    // mtfFromPsf on a sampled Gaussian equals the Gaussian closed form (MTF50, MTF10).
    const int n = 512;
    const double sample = 0.5, w = 20.0;  // arcmin
    cv::Mat g(n, n, CV_64F);
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const double r2 = (std::pow(x - n / 2, 2) + std::pow(y - n / 2, 2)) * sample * sample;
        g.at<double>(y, x) = std::exp(-2 * r2 / (w * w));
      }
    g /= cv::sum(g)[0];
    const MtfCurve m = mtfFromPsf(g, sample);
    const SpotMetrics c = gaussianSpotMetrics(w);
    QVERIFY(std::abs(m.frequencyAt(0.5) / c.mtf50_cpd - 1) < 0.01);
    QVERIFY(std::abs(m.frequencyAt(0.1) / c.mtf10_cpd - 1) < 0.01);
    QVERIFY(std::abs(psfFwhmArcmin(g, sample) / c.fwhm_arcmin - 1) < 0.01);
  }

  void peripheralAllInFocusFovealNot() {
    const Scene s = embeddedDefaultScene();
    for (double wl : s.projector.wavelengths_nm) {
      const PeripheralSpot a = peripheralSpot(s, wl, 0.4, {0, 0});
      const PeripheralSpot b = peripheralSpot(s, wl, 3.3, {0, 0});
      QVERIFY(a.valid && b.valid);
      const double change = b.metrics.fwhm_arcmin / a.metrics.fwhm_arcmin - 1;
      qInfo(
          "peripheral %g nm: FWHM %.2f arcmin at 0.4 D, %.2f at 3.3 D (%+.2f %%); MTF50 %.3f cpd; beam at HOE %.3f mm, "
          "pupil %.4f mm; HOE %.1f D",
          wl, a.metrics.fwhm_arcmin, b.metrics.fwhm_arcmin, 100 * change, a.metrics.mtf50_cpd, a.beam_radius_hoe_mm,
          a.beam_radius_pupil_mm, a.hoe_power_d);
      QVERIFY(std::abs(change) < 0.05);
      QVERIFY(a.pupil_transmission > 0.999);
    }
    // With a beam-shaping lens that images the beam near the plate, the pixel on the HOE and
    // so on the retina shrinks (the seed's A.2): LB1471-like f = 50 mm at 62.7 mm on the axis.
    Scene lensed = s;
    lensed.lens.enabled = true;
    lensed.lens.focal_length_mm = 50.0;
    {
      const Frame pf = frameOf(s.projector.pose);
      lensed.lens.pose.position_mm = fromVec(pf.origin + 62.7 * pf.z());
    }
    const PeripheralSpot with = peripheralSpot(lensed, 532, 1.25, {0, 0});
    const PeripheralSpot without = peripheralSpot(s, 532, 1.25, {0, 0});
    qInfo(
        "with an f = 50 mm lens at 62.7 mm: beam at HOE %.4f mm (was %.4f), FWHM %.2f arcmin, MTF50 %.2f cpd, MTF10 "
        "%.2f cpd",
        with.beam_radius_hoe_mm, without.beam_radius_hoe_mm, with.metrics.fwhm_arcmin, with.metrics.mtf50_cpd,
        with.metrics.mtf10_cpd);
    QVERIFY(with.through_lens);
    QVERIFY(with.metrics.fwhm_arcmin < without.metrics.fwhm_arcmin);
    // Foveal (virtual image at 0.8 m = 1.25 D): sharp in focus, blurred as pupil x |dD| away.
    const FovealSpot in = fovealSpot(s, 530, 1.25, {0, 0});
    const FovealSpot near = fovealSpot(s, 530, 3.3, {0, 0});
    const FovealSpot far = fovealSpot(s, 530, 0.4, {0, 0});
    qInfo(
        "foveal 530 nm: FWHM %.2f / %.2f / %.2f arcmin at 1.25 / 3.3 / 0.4 D (geometric %.1f, %.1f); MTF50 %.1f / %.2f "
        "/ %.2f cpd",
        in.metrics.fwhm_arcmin, near.metrics.fwhm_arcmin, far.metrics.fwhm_arcmin, near.geometric_blur_arcmin,
        far.geometric_blur_arcmin, in.metrics.mtf50_cpd, near.metrics.mtf50_cpd, far.metrics.mtf50_cpd);
    QVERIFY(near.metrics.fwhm_arcmin > 5 * in.metrics.fwhm_arcmin);
    QVERIFY(far.metrics.fwhm_arcmin > 5 * in.metrics.fwhm_arcmin);
    // EE50 of the defocus disc: diameter / sqrt(2).
    QVERIFY(std::abs(near.eye_only.fwhm_arcmin / (near.geometric_blur_arcmin / std::sqrt(2.0)) - 1) < 0.05);
  }

  // The foveal PSF is the line of sight's over the whole inset (docs/physics.md): the combiner's
  // aberration blur and field curvature off the axis are bounded here rather than modelled. At
  // the blend end (the outermost foveal content, B.2.3) the traced combiner's extra RMS blur,
  // convolved into the in-focus 530 nm line-of-sight PSF, lowers its MTF50 by under 5 %
  // (measured 3.3 %), and its best focus moves by under 0.01 D (measured 0.003 D: a defocus disc
  // of 5 mm x 0.003 D = 0.06 arcmin, against the 1.6 arcmin spot).
  void combinerFieldDependenceIsSmallOverTheInset() {
    const Scene s = embeddedDefaultScene();
    const double edge_deg = s.foveation.blend_end_deg;
    const FovealOpticsSample axis = tracedCombinerMtf30(s, 0, 0), edge = tracedCombinerMtf30(s, 0, edge_deg);
    const double extra_sigma_arcmin = std::sqrt(
        std::max(0.0, edge.rms_blur_arcmin * edge.rms_blur_arcmin - axis.rms_blur_arcmin * axis.rms_blur_arcmin));
    const FovealSpot in = fovealSpot(s, 530, 1.25, {0, 0});
    const double mtf50_axis = mtfFromPsf(in.psf, in.sample_arcmin).frequencyAt(0.5);
    const double mtf50_edge = mtfFromPsf(in.psf, in.sample_arcmin, 0, extra_sigma_arcmin).frequencyAt(0.5);
    const double focus_shift_d = std::abs(1000.0 / axis.best_focus_mm - 1000.0 / edge.best_focus_mm);
    qInfo(
        "combiner at %.1f deg: RMS blur %.3f arcmin (axis %.3f), MTF50 %.2f -> %.2f cpd (%.2f %%), best focus %.1f -> "
        "%.1f mm (%.4f D)",
        edge_deg, edge.rms_blur_arcmin, axis.rms_blur_arcmin, mtf50_axis, mtf50_edge,
        100 * (1 - mtf50_edge / mtf50_axis), axis.best_focus_mm, edge.best_focus_mm, focus_shift_d);
    QVERIFY(std::abs(mtf50_axis / in.metrics.mtf50_cpd - 1) < 0.02);  // the same MTF as the spot's own
    QVERIFY(edge.rms_blur_arcmin > axis.rms_blur_arcmin);             // it does grow off the axis
    QVERIFY(mtf50_edge < mtf50_axis);
    QVERIFY(1 - mtf50_edge / mtf50_axis < 0.05);
    QVERIFY(focus_shift_d < 0.01);
  }

  void speckleContrastIsOneOverRootN() {
    for (int n : {1, 3, 5, 15}) {
      const cv::Mat f = image::speckleField(cv::Size(400, 400), n, 42 + n);
      const double c = image::speckleContrast(f);
      qInfo("speckle N=%d: contrast %.4f vs %.4f", n, c, 1 / std::sqrt(n));
      QVERIFY(std::abs(c * std::sqrt(n) - 1) < 0.05);
      // docs/physics.md prints 1.0006, 0.5768, 0.4458, 0.2588: held to those digits.
      const double printed = n == 1 ? 1.0006 : n == 3 ? 0.5768 : n == 5 ? 0.4458 : 0.2588;
      QVERIFY2(std::abs(c - printed) < 5e-5, qPrintable(QString::number(c, 'g', 6)));
    }
  }

  void uniformFieldHasNoRayRipple() {
    // A white target: away from the edges and the foveal disc, the retinal image varies only
    // as slowly as the efficiency map, not with the ray grid (cells are splatted as areas).
    const Scene s = embeddedDefaultScene();
    const cv::Mat target(277, 480, CV_32FC3, cv::Scalar(1, 1, 1));
    image::RetinaImageOptions o;
    o.rays = 20000;
    o.blend = false;
    const auto r = image::renderRetinaImage(s, target, o);
    double worst = 0;
    for (int x = 60; x + 4 < 160; ++x) {
      const double a = r.image.at<cv::Vec3f>(40, x)[1], b = r.image.at<cv::Vec3f>(40, x + 4)[1];
      worst = std::max(worst, std::abs(b / a - 1));
    }
    qInfo("largest change over 4 px (1/3 deg) on a white field: %.4f", worst);
    QVERIFY(worst < 0.01);
  }

  void peripheralEdgeHasThePsfWidth() {
    // A vertical edge (white left of yaw -12 deg) seen at gaze +10 deg, 22 deg out, where only
    // the projector shows it. The PSF is field-dependent (retina_image.cpp): each ray's power
    // is shared between the nodes at world yaw -20 and -10 deg by linear weights and blurred by
    // each node's elliptical Gaussian. Along a vertical edge only the horizontal variance
    // sigma_x^2 of each counts; the expected edge is that 1-D model computed here, its 10-90 %
    // width compared with the image's. The wide PSFs run on the coarse grid; the ray cells add
    // a box of about a third of a degree (variance under 1 % of sigma^2), so within 3 %.
    const Scene s = embeddedDefaultScene();
    const cv::Size size(960, 540);
    cv::Mat target(size, CV_32FC3, cv::Scalar(0, 0, 0));
    const double fov_x = s.projector.fov_deg[0], ppd = size.width / fov_x;
    const double edge_deg = -12.0;
    const int edge_px = static_cast<int>(std::lround((edge_deg / fov_x + 0.5) * size.width));
    target(cv::Rect(0, 0, edge_px, size.height)).setTo(cv::Scalar(1, 1, 1));
    image::RetinaImageOptions o;
    o.gaze_deg = {10.0, 0.0};
    o.rays = 20000;
    const auto r = image::renderRetinaImage(s, target, o);
    // The reference laser's nodes on the horizon at -20 and -10 deg.
    const std::size_t n_nodes = r.peripheral_field.size() / s.projector.wavelengths_nm.size();
    double sigma_a = 0, sigma_b = 0;  // deg, at -20 and -10
    for (std::size_t z = 0; z < n_nodes; ++z) {
      const auto& f = r.peripheral_field[r.peripheral_reference * n_nodes + z];
      if (std::abs(f.world_deg[1]) > 1e-9) continue;
      const double sx = std::sqrt(f.spot.covariance_arcmin2[0]) / 60.0;
      if (std::abs(f.world_deg[0] + 20) < 1e-9) sigma_a = sx;
      if (std::abs(f.world_deg[0] + 10) < 1e-9) sigma_b = sx;
      if (std::abs(f.world_deg[0] + 10) < 1e-9) {
        qInfo(
            "node at -10 deg: spot %.1f x %.1f arcmin (1/e^2), axis %.1f deg, HOE astigmatism %.2f D; eye %.1f deg "
            "off its axis, its powers %+.2f / %+.2f D",
            f.spot.radius_major_arcmin, f.spot.radius_minor_arcmin, f.spot.orientation_deg, f.spot.astigmatism_d,
            f.spot.eye_field_deg, f.spot.eye_power_d[0], f.spot.eye_power_d[1]);
        // docs/physics.md: the HOE's 5.5 D there dwarfs the eye's own (0.85 D at 19.5 deg).
        QVERIFY2(std::abs(f.spot.astigmatism_d - 5.5) <= 0.05, qPrintable(QString::number(f.spot.astigmatism_d)));
        // The beam enters the pupil off its centre (a 10 deg gaze the HOE does not follow): the
        // eye's power is the decentred pencil's (eye_oblique_focus.h), not the chief ray's.
        const SchematicEyeState eye_state = navarroEye(o.accommodation_d, f.spot.wavelength_nm);
        const EyeObliqueFocus eye = eyeObliqueFocus(eye_state, f.spot.eye_field_deg);
        const EyePencilPower pencil =
            eyePencilPower(eye_state, f.spot.eye_field_deg, f.spot.pupil_offset_mm[0], f.spot.pupil_offset_mm[1]);
        qInfo(
            "  enters %.2f / %.2f mm (meridional / sagittal) off the pupil centre: eye powers %+.2f / %+.2f D, cross "
            "%+.2f D"
            " (the chief ray's %+.2f / %+.2f)",
            f.spot.pupil_offset_mm[0], f.spot.pupil_offset_mm[1], pencil.meridional_d, pencil.sagittal_d,
            pencil.cross_d, eye.power_tangential_d, eye.power_sagittal_d);
        QVERIFY(f.spot.eye_field_deg > 15 && f.spot.eye_field_deg < 25);
        QVERIFY(std::hypot(f.spot.pupil_offset_mm[0], f.spot.pupil_offset_mm[1]) > 1.0);
        QCOMPARE(f.spot.eye_power_d[0], pencil.meridional_d);
        QCOMPARE(f.spot.eye_power_d[1], pencil.sagittal_d);
        QCOMPARE(f.spot.eye_power_cross_d, pencil.cross_d);
        QVERIFY2(std::abs(eye.astigmatism_d - 0.85) <= 0.005, qPrintable(QString::number(eye.astigmatism_d)));
      }
    }
    QVERIFY(sigma_a > 0 && sigma_b > 0);
    // 1-D model: white for x' < edge; weight of node a (1 - t), of node b t, t = (x' + 20)/10.
    const double step = 0.005;
    auto model = [&](double x) {
      double v = 0;
      for (double xp = edge_deg - 10; xp < edge_deg; xp += step) {
        const double t = std::clamp((xp + 20.0) / 10.0, 0.0, 1.0);
        auto g = [&](double sg) {
          return std::exp(-0.5 * (x - xp) * (x - xp) / (sg * sg)) / (sg * std::sqrt(2 * kPi));
        };
        v += step * ((1 - t) * g(sigma_a) + t * g(sigma_b));
      }
      return v;
    };
    const double sigma_px = std::max(sigma_a, sigma_b) * ppd;
    std::vector<double> expect_profile(static_cast<std::size_t>(size.width), 0.0);
    for (int x = 0; x < size.width; ++x)
      expect_profile[static_cast<std::size_t>(x)] = model(((x + 0.5) / size.width - 0.5) * fov_x);
    // Green channel (532 nm), averaged over rows around the horizon.
    std::vector<double> profile(static_cast<std::size_t>(size.width), 0.0);
    for (int y = size.height / 2 - 20; y <= size.height / 2 + 20; ++y)
      for (int x = 0; x < size.width; ++x) profile[static_cast<std::size_t>(x)] += r.image.at<cv::Vec3f>(y, x)[1];
    const int start = edge_px - static_cast<int>(4 * sigma_px);
    auto width_of = [&](const std::vector<double>& pr) {
      const double plateau = pr[static_cast<std::size_t>(start)];
      auto crossing = [&](double level) {
        for (int x = start; x + 1 < size.width; ++x) {
          const double a = pr[static_cast<std::size_t>(x)], b = pr[static_cast<std::size_t>(x + 1)];
          if (a >= level * plateau && b < level * plateau) return x + (a - level * plateau) / (a - b);
        }
        return -1.0;
      };
      return plateau > 0 ? crossing(0.1) - crossing(0.9) : -1.0;
    };
    const double width = width_of(profile), expected = width_of(expect_profile);
    qInfo("edge 10-90 %% width %.2f px, field-dependent model %.2f px (sigma_x %.2f / %.2f px at -20 / -10 deg)", width,
          expected, sigma_a * ppd, sigma_b * ppd);
    QVERIFY(width > 0 && expected > 0);
    QVERIFY2(std::abs(width / expected - 1) < 0.03, qPrintable(QString::number(width / expected)));
    // docs/physics.md prints "70.39 px against 70.25 px": held to those digits (70.29 / 70.13
    // before the eye's own off-axis astigmatism entered the spots, 70.27 / 70.11 with the chief
    // ray's pencil for every beam, before the beam's 2 mm decentration in the pupil entered).
    QVERIFY2(std::abs(width - 70.39) <= 0.005, qPrintable(QString::number(width, 'f', 4)));
    QVERIFY2(std::abs(expected - 70.25) <= 0.005, qPrintable(QString::number(expected, 'f', 4)));
  }

  void lateralColourFollowsTheGratingEquation() {
    // Line of sight, gaze 0: the pixel meeting the plate centre. The green laser is on its
    // layer's wavelength, so it reaches the pupil centre along the axis; red and blue leave at
    // yaw asin((1 - mu) 90 / |(90, 0, -70)|) (grating_yaw_deg at theta = 0), pitch 0.
    const Scene s = offsetLasers();
    const auto lc = lateralColourAtLineOfSight(s, {0, 0});
    QCOMPARE(lc.size(), std::size_t{3});
    const Vec3mm ref = s.hoe_layers[0].recording.reference_point_mm;
    const std::array<double, 3> rec{660.0, 532.0, 460.0};
    for (std::size_t i = 0; i < 3; ++i) {
      QVERIFY(lc[i].valid);
      const double mu = s.projector.wavelengths_nm[i] / rec[i];
      const double expect_arcmin = 60.0 * grating_yaw_deg(0.0, mu, ref, s.eye.relief_mm);
      qInfo("%g nm: lateral colour %.6f, %.2e arcmin (grating equation %.6f arcmin)", lc[i].wavelength_nm,
            lc[i].offset_arcmin[0], lc[i].offset_arcmin[1], expect_arcmin);
      QVERIFY2(std::abs(lc[i].offset_arcmin[0] - expect_arcmin) < 1e-7, qPrintable(QString::number(expect_arcmin)));
      QVERIFY(std::abs(lc[i].offset_arcmin[1]) < 1e-7);
    }
    QVERIFY(std::abs(lc[0].offset_arcmin[0]) > 30);  // red: 41 arcmin, not zero
    // The prototype (lasers on their layers' wavelengths): no lateral colour.
    for (const auto& c : lateralColourAtLineOfSight(embeddedDefaultScene(), {0, 0}))
      QVERIFY(c.valid && std::hypot(c.offset_arcmin[0], c.offset_arcmin[1]) < 1e-7);
  }

  void retinalImageShowsPerLayerFringes() {
    // A white blob at world yaw 10 deg (beyond the foveal blend: only the projector shows it),
    // gaze 0. With one calibration for all lasers (the green one's), the red and blue channels
    // are displaced by the grating equation's lateral colour at 10 deg; with each laser warped
    // on its own they are not. The difference of the two renders' channel centroids removes
    // what both share (the efficiency map's slope across the blob, the cells' sampling).
    const Scene s = offsetLasers();
    const double theta = 10.0;
    const BlobRenders r = blobRenders(s, theta);
    const image::DisplayAngles& ang = r.ang;
    const image::RetinaImageResult &common = r.common, &own = r.own;
    const Vec3mm ref = s.hoe_layers[0].recording.reference_point_mm;
    const std::array<double, 3> rec{660.0, 532.0, 460.0};
    for (int k = 0; k < 3; ++k) {
      const double mu = s.projector.wavelengths_nm[static_cast<std::size_t>(k)] / rec[static_cast<std::size_t>(k)];
      const double expect = grating_yaw_deg(theta, mu, ref, s.eye.relief_mm) - theta;
      const auto a = channelCentroidDeg(common.image, ang, k, theta - 7, theta + 7);
      const auto b = channelCentroidDeg(own.image, ang, k, theta - 7, theta + 7);
      qInfo("channel %d: fringe %.2f arcmin yaw, %.2f pitch (grating equation %.2f arcmin); own warp at %.3f deg", k,
            60 * (a[0] - b[0]), 60 * (a[1] - b[1]), 60 * expect, b[0]);
      if (k == 1) {
        QVERIFY(std::abs(a[0] - b[0]) * 60 < 0.05);  // the calibration colour: unchanged
      } else {
        QVERIFY2(std::abs((a[0] - b[0]) / expect - 1) < 0.03, qPrintable(QString::number(60 * (a[0] - b[0]))));
      }
      QVERIFY(std::abs(a[1] - b[1]) * 60 < 0.5);  // horizontal plane: no vertical fringe
    }
  }

  void symmetricSceneHasNoFringeOnAxis() {
    // Reference point and projector on the plate's normal through its centre (an on-axis
    // hologram): at the centre r_t = s_t = 0, so every wavelength leaves along the axis; off
    // axis the lateral colour is radial, as the grating equation gives it.
    Scene s = offsetLasers();
    for (auto& l : s.hoe_layers) l.recording.reference_point_mm = {0.0, 0.0, -70.0};
    s.projector.pose.position_mm = {0.0, 0.0, -70.0};
    s.projector.pose.rotation_deg = {0.0, 0.0, 0.0};
    for (const auto& c : lateralColourAtLineOfSight(s, {0, 0})) {
      qInfo("on-axis hologram, %g nm: lateral colour %.2e, %.2e arcmin", c.wavelength_nm, c.offset_arcmin[0],
            c.offset_arcmin[1]);
      QVERIFY(c.valid);
      QVERIFY(std::hypot(c.offset_arcmin[0], c.offset_arcmin[1]) < 1e-7);
    }
    const double theta = 10.0;
    const BlobRenders r = blobRenders(s, theta);
    const image::DisplayAngles& ang = r.ang;
    const image::RetinaImageResult &common = r.common, &own = r.own;
    const double expect = grating_yaw_deg(theta, 650.0 / 660.0, {0.0, 0.0, -70.0}, s.eye.relief_mm) - theta;
    const auto a = channelCentroidDeg(common.image, ang, 0, theta - 7, theta + 7);
    const auto b = channelCentroidDeg(own.image, ang, 0, theta - 7, theta + 7);
    qInfo("on-axis hologram, red at 10 deg: fringe %.2f arcmin (grating equation %.2f)", 60 * (a[0] - b[0]),
          60 * expect);
    QVERIFY2(std::abs((a[0] - b[0]) / expect - 1) < 0.03, qPrintable(QString::number(60 * (a[0] - b[0]))));
  }

  void hologramAstigmatismIsCoddingtons() {
    // Plate z = 0, reference point and signal point of the prototype, a plate point on the
    // horizontal meridian (all rays in the x-z plane of incidence), a laser 10 nm off its layer
    // and a Gaussian beam from the reference point: the tangential and sagittal sections
    // separate and follow the holographic Coddington equations (hologram_astigmatism.h):
    //   cos^2 th_o / q'_t = cos^2 th_i / q_t - mu (cos^2 th_s / L_s + cos^2 th_r / L_r)
    //   1 / q'_s = 1 / q_s - mu (1 / L_s + 1 / L_r)
    HologramPointGeometry g;
    g.point = Eigen::Vector3d(6.0, 0.0, 0.0);
    g.reference_mm = Eigen::Vector3d(90.0, 0.0, -70.0);
    g.signal_mm = Eigen::Vector3d(0.0, 0.0, -22.0);
    g.mu = 650.0 / 660.0;
    const Eigen::Vector3d u_in = (g.point - g.reference_mm).normalized();
    const Eigen::Vector3d u_out = hologramOutDirection(g, u_in, Eigen::Vector3d(0, 0, -1));
    QVERIFY(u_out.z() < 0);
    // Basis normal to u_out: the in-plane (tangential) direction and y (sagittal).
    Eigen::Matrix<double, 3, 2> b;
    b.col(0) = Eigen::Vector3d(-u_out.z(), 0.0, u_out.x()).normalized();
    b.col(1) = Eigen::Vector3d::UnitY();
    const std::complex<double> q(-36.0, 500.0);
    const Eigen::Matrix2cd m = hologramOutputCurvature(g, u_in, q, u_out, b);
    const double l_r = (g.point - g.reference_mm).norm(), l_s = (g.signal_mm - g.point).norm();
    const double c_i = std::abs(u_in.z()), c_o = std::abs(u_out.z()), c_r = c_i;
    const double c_s = std::abs((g.signal_mm - g.point).z()) / l_s;
    // out_x from the grating equation (tangential components), independently of the code.
    const double out_x = u_in.x() + g.mu * ((g.signal_mm - g.point).x() / l_s - u_in.x());
    QVERIFY(std::abs(std::sqrt(1 - out_x * out_x) - c_o) < 1e-14);
    const std::complex<double> t_expect = (c_i * c_i / q - g.mu * (c_s * c_s / l_s + c_r * c_r / l_r)) / (c_o * c_o);
    const std::complex<double> s_expect = 1.0 / q - g.mu * (1.0 / l_s + 1.0 / l_r);
    qInfo("tangential %.9f%+.9fi, sagittal %.9f%+.9fi 1/mm (Coddington %.9f, %.9f); astigmatism %.3f D", m(0, 0).real(),
          m(0, 0).imag(), m(1, 1).real(), m(1, 1).imag(), t_expect.real(), s_expect.real(),
          1000 * (m(0, 0).real() - m(1, 1).real()));
    QVERIFY(std::abs(m(0, 0) - t_expect) < 1e-12 * std::abs(t_expect));
    QVERIFY(std::abs(m(1, 1) - s_expect) < 1e-12 * std::abs(s_expect));
    QVERIFY(std::abs(m(0, 1)) < 1e-14 && std::abs(m(1, 0)) < 1e-14);
    QVERIFY(std::abs(m(0, 0).real() - m(1, 1).real()) * 1000 > 1.0);  // off-axis: astigmatic
  }

  void hologramAstigmatismLimits() {
    // Limit 1: a point source at the reference point, at the recording wavelength, anywhere on
    // the plate (here off both meridians: the cross terms count) is imaged stigmatically on
    // the signal point: M = -I / L_s.
    HologramPointGeometry g;
    g.point = Eigen::Vector3d(9.0, -7.0, 0.0);
    g.reference_mm = Eigen::Vector3d(90.0, 0.0, -70.0);
    g.signal_mm = Eigen::Vector3d(0.0, 0.0, -22.0);
    const Eigen::Vector3d u_in = (g.point - g.reference_mm).normalized();
    const Eigen::Vector3d u_out = hologramOutDirection(g, u_in, Eigen::Vector3d(0, 0, -1));
    const double l_s = (g.signal_mm - g.point).norm();
    QVERIFY((u_out - (g.signal_mm - g.point) / l_s).norm() < 1e-14);
    Eigen::Matrix<double, 3, 2> b;
    b.col(0) = u_out.cross(Eigen::Vector3d::UnitY()).normalized();
    b.col(1) = u_out.cross(b.col(0));
    const Eigen::Matrix2cd m =
        hologramOutputCurvature(g, u_in, std::complex<double>((g.point - g.reference_mm).norm(), 0.0), u_out, b);
    const Eigen::Matrix2cd expect = -Eigen::Matrix2cd::Identity() / l_s;
    qInfo("point source at the reference, (9, -7): |M + I/L_s| = %.2e 1/mm", (m - expect).norm());
    QVERIFY((m - expect).norm() < 1e-12 / l_s);
    // Limit 2: an on-axis hologram (reference and projector on the plate's normal through the
    // line of sight's plate point) has no astigmatism on axis: the spot is round and is the
    // scalar chain's (thin lens mu (1/L_r + 1/L_s), free space, the eye's ABCD).
    Scene s = embeddedDefaultScene();
    for (auto& l : s.hoe_layers) l.recording.reference_point_mm = {0.0, 0.0, -70.0};
    s.projector.pose.position_mm = {0.0, 0.0, -70.0};
    s.projector.pose.rotation_deg = {0.0, 0.0, 0.0};
    s.projector.wavelengths_nm = {650.0, 532.0, 450.0};
    for (double wl : s.projector.wavelengths_nm) {
      const PeripheralSpot p = peripheralSpot(s, wl, 1.0, {0, 0});
      QVERIFY(p.valid);
      QVERIFY(p.astigmatism_d < 1e-9);
      QVERIFY(std::abs(p.radius_major_arcmin / p.radius_minor_arcmin - 1) < 1e-9);
      const PixelBeamModel& pb = s.projector.pixel_beam;
      const double w0 = pb.waist_fwhm_um * 1e-3 / 1.1774100225154747,
                   th = pb.divergence_mrad * 1e-3 / 1.1774100225154747;
      std::complex<double> q(70.0 - pb.waist_distance_mm, w0 / th);
      const double rec = wl > 600 ? 660.0 : wl > 500 ? 532.0 : 460.0;
      q = transformQ(thinLens(wl / rec * (1.0 / 70.0 + 1.0 / 22.0)), q);
      q = transformQ(freeSpace(22.0), q);
      const SchematicEyeState e = navarroEye(1.0, wl);
      q = transformQ(e.pupil_to_retina, q);
      const double w = gaussianRadiusMm(q, kPi * w0 * th) / e.retina_mm_per_rad * kArcmin;
      qInfo("on-axis hologram %g nm: spot %.6f x %.6f arcmin, scalar chain %.6f", wl, p.radius_major_arcmin,
            p.radius_minor_arcmin, w);
      QVERIFY(std::abs(p.radius_1e2_arcmin / w - 1) < 1e-9);
    }
  }

  void speckleGrainSetByThePupil() {
    // Degrees of freedom of a pixel integrating Airy-correlated speckle (speckle_grain.h):
    // M -> 1 for a pixel far under the grain lambda/D, M -> a b / Omega_c (Omega_c =
    // 4 lambda^2 / (pi D^2)) for one far over it.
    const double wl = 550.0, d = 5.0;
    const double grain = wl * 1e-6 / d / (kDeg / 60.0);  // lambda/D in arcmin
    const double omega = image::speckleCorrelationAreaArcmin2(wl, d);
    QVERIFY(std::abs(omega / (4 * grain * grain / kPi) - 1) < 1e-12);
    const double small = image::speckleDegreesOfFreedom(0.01 * grain, 0.01 * grain, wl, d);
    QVERIFY2(std::abs(small - 1) < 1e-3, qPrintable(QString::number(small, 'g', 8)));
    double last = small;
    for (double k : {0.5, 1.0, 3.0, 10.0, 30.0, 100.0}) {
      const double m = image::speckleDegreesOfFreedom(k * grain, k * grain, wl, d);
      qInfo("pixel %5.1f lambda/D: M = %.4f, asymptote a^2/Omega_c = %.4f (ratio %.4f)", k, m,
            k * k * grain * grain / omega, m / (k * k * grain * grain / omega));
      QVERIFY(m > last);
      last = m;
    }
    QVERIFY(std::abs(last / (1e4 * grain * grain / omega) - 1) < 0.05);
    // The 1080p prototype image (1.25 arcmin pixels) at 532 nm, 5 mm pupil.
    const double m1080 = image::speckleDegreesOfFreedom(40.0 * 60 / 1920, 23.1 * 60 / 1080, 532.0, 5.0);
    qInfo("1080p canvas pixel, 532 nm: grain lambda/D %.3f arcmin, M = %.2f, contrast %.3f per pattern",
          532e-6 / 5.0 / (kDeg / 60.0), m1080, 1 / std::sqrt(m1080));
    QVERIFY(m1080 > 3 && m1080 < 20);
    // The gamma field's contrast is 1/sqrt(dof).
    for (double dof : {1.0, 2.5, 9.0}) {
      const double c = image::speckleContrast(image::integratedSpeckleField(cv::Size(400, 400), dof, 7));
      qInfo("dof %.1f: contrast %.4f vs %.4f", dof, c, 1 / std::sqrt(dof));
      QVERIFY(std::abs(c * std::sqrt(dof) - 1) < 0.05);
    }
    // In the retinal image: the measured speckle contrast is the model's sqrt(sum 1/(M_l N))/L.
    const Scene s = embeddedDefaultScene();
    const cv::Mat target = image::makeTestTarget(cv::Size(640, 370), s.projector.fov_deg, 20.0);
    image::RetinaImageOptions o;
    o.rays = 4000;
    o.speckle_patterns = 2;
    o.speckle_grain_pupil = true;
    const auto r = image::renderRetinaImage(s, target, o);
    QVERIFY(r.speckle_contrast && r.speckle_expected);
    QCOMPARE(r.speckle_dof.size(), std::size_t{3});
    qInfo("retinal image 640 px, 2 patterns, pupil grain: M = %.2f / %.2f / %.2f, contrast %.4f vs %.4f",
          r.speckle_dof[0], r.speckle_dof[1], r.speckle_dof[2], *r.speckle_contrast, *r.speckle_expected);
    QVERIFY(r.speckle_dof[2] > r.speckle_dof[0]);  // blue: finer grain, more of it per pixel
    QVERIFY(std::abs(*r.speckle_contrast / *r.speckle_expected - 1) < 0.05);
    QVERIFY(std::abs(r.power_on_retina - r.power_in_pupil) <= 1e-6 * r.power_in_pupil);
  }
  void retinalImageConservesPupilPower() {
    const Scene s = embeddedDefaultScene();
    const cv::Mat target = image::makeTestTarget(cv::Size(640, 370), s.projector.fov_deg, 20.0);
    for (int patterns : {0, 2}) {
      image::RetinaImageOptions o;
      o.rays = 4000;
      o.speckle_patterns = patterns;
      o.accommodation_d = 2.0;
      const auto r = image::renderRetinaImage(s, target, o);
      qInfo("speckle %d: power in pupil %.6f, on retina %.6f (rel. %.2e), rays in pupil %d", patterns, r.power_in_pupil,
            r.power_on_retina, (r.power_on_retina - r.power_in_pupil) / r.power_in_pupil, r.rays_in_pupil);
      QVERIFY(r.power_in_pupil > 0);
      QVERIFY(std::abs(r.power_on_retina - r.power_in_pupil) <= 1e-6 * r.power_in_pupil);
      QCOMPARE(r.image.size(), target.size());
      QCOMPARE(r.speckle_contrast.has_value(), patterns > 0);
    }
  }
};

QTEST_GUILESS_MAIN(TestRetinalPsf)

}  // namespace tst_retinal_psf
#include "tst_retinal_psf.moc"

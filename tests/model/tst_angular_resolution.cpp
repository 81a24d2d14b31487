// Angular resolution vs eccentricity (A.5): the pixel-count integrals, symmetry, limits.
#include <QtTest>

#include <cmath>

#include "app/embedded_scene.h"
#include "model/analysis/angular_resolution.h"
#include "model/scene/scene_io.h"
#include "model/units.h"

namespace tst_angular_resolution {

using namespace fovea;

namespace {
using fovea::embeddedDefaultScene;
}  // namespace

class TestAngularResolution : public QObject {
  Q_OBJECT
 private slots:
  void wholeProjectionOnHoeGivesBackEveryPixel() {
    // A HOE large enough to catch the whole projection: integrating 2 c_p (pixels per
    // degree of eccentricity) along the gaze row must count all N_px projector columns.
    Scene s = embeddedDefaultScene();
    s.hoe.size_mm = {400.0, 400.0};
    const ResolutionResult r = analyzeResolution(s);
    QCOMPARE(r.pixels_horizontal, 1280);
    QVERIFY2(std::abs(r.peripheral_pixel_integral - 1280.0) < 1.0,
             qPrintable(QString::number(r.peripheral_pixel_integral)));
  }

  void prototypeCountsThePixelsLandingOnTheHoe() {
    const Scene s = embeddedDefaultScene();
    const ResolutionResult r = analyzeResolution(s);
    // Independent count: projector columns whose horizontal angle phi falls between the
    // HOE's left and right edges on the gaze row (exact edge geometry, no eccentricity).
    const auto phi_l = projectionAngleForEccentricity(s, 0, 0, r.peripheral_field_deg[0], {0, 0}, false);
    const auto phi_r = projectionAngleForEccentricity(s, 0, 0, r.peripheral_field_deg[1], {0, 0}, false);
    QVERIFY(phi_l && phi_r);
    int columns = 0;
    for (int i = 0; i < 1280; ++i) {
      const double phi = -20.0 + 40.0 * (i + 0.5) / 1280;
      if (phi >= std::min(*phi_l, *phi_r) && phi <= std::max(*phi_l, *phi_r)) ++columns;
    }
    QVERIFY(std::abs(r.peripheral_pixel_integral - columns) <= 1.0);
    QVERIFY(columns < 1280);  // the projection overfills the HOE (A.3)
    // The field seen at zero gaze spans the HOE as seen from the pupil: 2 atan(22/22) = 90 deg.
    QVERIFY(std::abs(r.peripheral_field_deg[0] + 45.0) < 0.01);
    QVERIFY(std::abs(r.peripheral_field_deg[1] - 45.0) < 0.01);
  }

  void fovealIntegralAndCentreValue() {
    const Scene s = embeddedDefaultScene();
    const ResolutionResult r = analyzeResolution(s);
    QVERIFY(std::abs(r.foveal_pixel_integral - 1920.0) < 0.5);
    // On axis: 1920 px across 15.55 mm * 21.9 at 800 + 11.5 mm from the eye's centre...
    // c_f(0) = 1/2 k_f d_f (per rad): k_f = 1920 / (21.9 * 15.55) px/mm.
    const double k_f = 1920.0 / (21.9 * 15.55);
    const double expected = 0.5 * k_f * 800.0 * kDeg;
    const auto mid = r.samples[r.samples.size() / 2];
    QVERIFY(std::abs(mid.eccentricity_deg) < 1e-9);
    QVERIFY(mid.foveal_cpd.has_value());
    QVERIFY(std::abs(*mid.foveal_cpd - expected) < 1e-9);
    // Field of the micro-OLED image: +-atan(M w / 2 / d_f) = +-12.0 deg.
    const double half = std::atan(21.9 * 15.55 / 2 / 800.0) / kDeg;
    QVERIFY(std::abs(r.foveal_field_deg[1] - half) < 1e-9 && std::abs(r.foveal_field_deg[0] + half) < 1e-9);
    QCOMPARE(*mid.optical_limit_model_cpd, 60.0);
    QCOMPARE(mid.perceived_cpd, std::min({expected, *mid.optical_limit_cpd, kEyeLimitCpd}));
  }

  void gazeRecentresTheFovealImage() {
    const Scene s = embeddedDefaultScene();
    ResolutionOptions o;
    o.gaze_deg = std::array<double, 2>{15.0, 0.0};
    const ResolutionResult r = analyzeResolution(s, o);
    // The image is recentred on the line of sight: its field is nearly symmetric about eps=0
    // and its pixel count is still all 1920 columns.
    QVERIFY(std::abs(r.foveal_pixel_integral - 1920.0) < 0.5);
    QVERIFY(std::abs(r.foveal_field_deg[0] + r.foveal_field_deg[1]) < 1.5);
    // Optical limit falls with field angle (field curvature): lower than at zero gaze.
    double best_optical = 0;
    for (const auto& smp : r.samples)
      if (smp.optical_limit_model_cpd) best_optical = std::max(best_optical, *smp.optical_limit_model_cpd);
    QVERIFY(best_optical < 60.0 * (1 - 0.0015 * 3.0 * 3.0) + 1e-9);
    // Outside the micro-OLED field there is no foveal value.
    QVERIFY(!r.samples.front().foveal_cpd.has_value());
  }

  void tracedCombinerIsDiffractionLimitedOnAxisAndFallsOffAxis() {
    const Scene s = embeddedDefaultScene();
    const CombinerPrescription c = combinerPrescription(s);
    // Mirror equation with M = v/u, v = d_f - b = 770 mm: f = v/(M-1), u = v/M.
    QVERIFY(std::abs(c.focal_length_mm - 770.0 / 20.9) < 1e-9);
    QVERIFY(std::abs(c.display_distance_mm - 770.0 / 21.9) < 1e-9);
    // f/7 mirror, 5 mm pupil: on axis only a trace of spherical aberration remains.
    const double diffraction = diffractionMtf30Cpd(5.0, 550.0);
    const FovealOpticsSample on = tracedCombinerMtf30(s, 0, 0);
    QVERIFY(on.mtf30_cpd <= diffraction + 1e-9);
    QVERIFY(on.mtf30_cpd > 0.95 * diffraction);
    QVERIFY(std::abs(on.best_focus_mm - 800.0) < 10.0);  // the eye focuses on the virtual image
    // Symmetric in field, worse off axis (field curvature / astigmatism), monotonic.
    double last = on.mtf30_cpd;
    for (double f : {3.0, 6.0, 9.0, 12.0}) {
      const double plus = tracedCombinerMtf30(s, 0, f).mtf30_cpd, minus = tracedCombinerMtf30(s, 0, -f).mtf30_cpd;
      QVERIFY(std::abs(plus - minus) < 1e-6 * plus);
      QVERIFY(plus < last);
      last = plus;
    }
    // Diffraction MTF30 scales with the pupil diameter over the wavelength.
    QVERIFY(std::abs(diffractionMtf30Cpd(2.5, 550.0) - diffraction / 2) < 1e-6 * diffraction);
  }

  void peripheralIsMirrorSymmetricForASymmetricBench() {
    // Projector straight in front of the HOE on the eye side, no tilt: c_p(eps) = c_p(-eps).
    Scene s = embeddedDefaultScene();
    s.projector.pose.position_mm = {0.0, 0.0, -60.0};
    s.projector.pose.rotation_deg = {0.0, 0.0, 0.0};
    s.projector.fov_deg = {60.0, 40.0};
    const ResolutionResult r = analyzeResolution(s);
    const auto& a = r.samples.front();
    const auto& b = r.samples.back();
    QVERIFY(a.peripheral_cpd && b.peripheral_cpd);
    QVERIFY(std::abs(*a.peripheral_cpd - *b.peripheral_cpd) < 1e-6 * *a.peripheral_cpd);
    QVERIFY(std::abs(a.eccentricity_deg + b.eccentricity_deg) < 1e-6);
  }
};

QTEST_GUILESS_MAIN(TestAngularResolution)

}  // namespace tst_angular_resolution
#include "tst_angular_resolution.moc"

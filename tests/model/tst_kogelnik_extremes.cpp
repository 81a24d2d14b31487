// Kogelnik at the extremes of its inputs: zero modulation gives zero diffraction for every
// absorption (exactly R(d) = exp(-alpha d / c_R), Kogelnik Eq. 19 with kappa = 0), overflowing
// absorption at grazing incidence gives no NaN dressed up as "full diffraction", and the
// planar-grating request refuses degenerate periods instead of printing null.
#include <QtTest>

#include <cmath>
#include <numbers>

#include "model/physics/grating_request.h"
#include "model/physics/kogelnik.h"

namespace tst_kogelnik_extremes {

using namespace fovea;

namespace {
GratingRequest request(double n1, double probe_deg, double absorption_per_mm) {
  GratingRequest r;
  r.grating.film.n0 = 1.5;
  r.grating.film.n1 = n1;
  r.grating.film.thickness_um = 16;
  r.grating.period_nm = 177.33;
  r.grating.slant_deg = 0;
  r.grating.probe_deg = probe_deg;
  r.grating.wavelength_nm = 532;
  r.absorption_per_mm = absorption_per_mm;
  return r;
}
}  // namespace

class TestKogelnikExtremes : public QObject {
  Q_OBJECT
 private slots:
  void zeroModulationNeverDiffracts_data() {
    QTest::addColumn<double>("probe_deg");
    QTest::addColumn<double>("absorption_per_mm");
    for (double probe : {0.0, 45.0, 89.0, 89.9999999999})
      for (double a : {0.0, 1e-3, 1.0, 1e3, 1e100, 1e300})
        QTest::newRow(qPrintable(QString("probe %1 absorption %2").arg(probe, 0, 'g', 13).arg(a))) << probe << a;
  }
  void zeroModulationNeverDiffracts() {
    QFETCH(double, probe_deg);
    QFETCH(double, absorption_per_mm);
    const GratingRequest r = request(0.0, probe_deg, absorption_per_mm);
    QVERIFY(!validateGratingRequest(r, false));
    const PlanarDiffraction d = diffractPlanar(planarGratingOf(r));
    QCOMPARE(d.grating.kogelnik.efficiency, 0.0);
    // |R(d)|^2 = exp(-absorption d / cos theta) (intensity absorption, path d / cos theta).
    const double c_r = std::cos(probe_deg * std::numbers::pi / 180.0);
    const double expected = std::exp(-absorption_per_mm * 16e-3 / c_r);
    QVERIFY2(std::abs(d.grating.kogelnik.zero_order - expected) <= 1e-12 + 1e-9 * expected,
             qPrintable(QString("zero order %1, expected %2").arg(d.grating.kogelnik.zero_order).arg(expected)));
  }

  // The issue's reproducer through the JSON answer: efficiency and zero order 0, every number finite.
  void issueReproducerAnswersZero() {
    const nlohmann::json j = kogelnikGratingJson(request(0.0, 89.9999999999, 1e300));
    QCOMPARE(j["efficiency"].get<double>(), 0.0);
    QCOMPARE(j["zero_order"].get<double>(), 0.0);
  }

  // Weak but nonzero modulation with an absorption whose alpha / c_R overflows: S is slaved to R
  // (|S| <= kappa |R| / alpha), so nothing is diffracted, and nothing is NaN.
  void overflowingAbsorptionIsOpaqueNotNaN() {
    for (double n1 : {1e-6, 0.01, 0.1})
      for (double probe : {89.9999999999, 60.0}) {
        const kogelnik::Result k = diffractPlanar(planarGratingOf(request(n1, probe, 1e300))).grating.kogelnik;
        QVERIFY(std::isfinite(k.efficiency) && std::isfinite(k.zero_order));
        QCOMPARE(k.efficiency, 0.0);
        QCOMPARE(k.zero_order, 0.0);
      }
  }

  // NaN is no longer clamped to 1: a NaN input shows up as NaN.
  void clampKeepsNaN() {
    QVERIFY(std::isnan(kogelnik::atMostOne(std::nan(""))));
    QCOMPARE(kogelnik::atMostOne(1.0 + 1e-15), 1.0);
    QCOMPARE(kogelnik::atMostOne(0.25), 0.25);
  }

  void degeneratePeriodIsAnError() {
    GratingRequest r = request(0.02, 0.0, 0.0);
    r.grating.period_nm = 1e-300;
    const auto e = validateGratingRequest(r, false);
    QVERIFY(e);
    QCOMPARE(
        QString::fromStdString(e->message),
        QString("period_nm: degenerate fringe period: must be at least 1e-6 wavelengths (got 1e-300 nm at 532 nm)"));
    r.grating.period_nm = 1e-3;  // 1.9e-6 wavelengths: evanescent, finite
    QVERIFY(!validateGratingRequest(r, false));
    const nlohmann::json j = kogelnikGratingJson(r);
    for (const char* key : {"xi", "c_s", "nu", "dephasing_per_um", "efficiency"})
      QVERIFY2(j[key].is_number() && std::isfinite(j[key].get<double>()), key);
    r.grating.film.thickness_um = 1e300;
    QVERIFY(validateGratingRequest(r, true));
    QCOMPARE(QString::fromStdString(validateGratingRequest(r, true)->key), QString("thickness_um"));
  }
};

QTEST_GUILESS_MAIN(TestKogelnikExtremes)

}  // namespace tst_kogelnik_extremes
#include "tst_kogelnik_extremes.moc"

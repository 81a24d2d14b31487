// RCWA behind `fovea-cli grating --model rcwa`: Kogelnik's inputs, index-matched defaults,
// polarisation averaging, absorption, automatic orders/slices, bad input.
#include <QtTest>

#include <cmath>

#include "model/rigorous/rcwa_grating.h"
#include "model/units.h"

namespace tst_rcwa_grating {

using namespace fovea::rigorous;
using fovea::kPi;

namespace {
RcwaGratingRequest transmissionOnBragg() {
  RcwaGratingRequest q;
  q.n0 = 1.5;
  q.n1 = 0.005;
  q.thickness_um = 20;
  q.period_nm = 500;
  q.slant_deg = 90;
  q.wavelength_nm = 532;
  q.probe_deg = std::asin(532.0 / (2 * 1.5 * 500)) * 180 / kPi;
  return q;
}
}  // namespace

class TestRcwaGrating : public QObject {
  Q_OBJECT
 private slots:
  void matchesKogelnikOnBragg() {
    const RcwaGratingRequest q = transmissionOnBragg();
    const RcwaGratingAnswer a = solveRcwaGrating(q);
    const double nu = kPi * q.n1 * q.thickness_um / (0.532 * std::cos(q.probe_deg * kPi / 180));
    QVERIFY(a.converged);
    QCOMPARE(a.kogelnik_order.order, 1);
    QVERIFY(!a.kogelnik_order.reflected);
    QVERIFY2(std::abs(a.efficiency - std::pow(std::sin(nu), 2)) < 1e-2, qPrintable(QString::number(a.efficiency)));
    QVERIFY(std::abs(a.total_efficiency - 1.0) < 1e-10);
    // Index-matched faces: the inside angle is the outside angle; +1 leaves at −θ_B (symmetric).
    bool found = false;
    for (const RcwaOrder& o : a.orders)
      if (o.order == 1 && !o.reflected) {
        QVERIFY(std::abs(o.angle_deg + q.probe_deg) < 1e-9);
        found = true;
      }
    QVERIFY(found);
    const nlohmann::json j = rcwaAnswerJson(a);
    QVERIFY(j.contains("efficiency") && j.contains("total_efficiency") && j["orders"].is_array());
    QCOMPARE(j["orders"][0]["side"].get<std::string>(), std::string("reflected"));
  }

  void unpolarisedIsTheMean() {
    RcwaGratingRequest q = transmissionOnBragg();
    q.orders = 4;
    q.slices = 1;
    q.polarization = GratingPolarization::S;
    const double s = solveRcwaGrating(q).efficiency;
    q.polarization = GratingPolarization::P;
    const double p = solveRcwaGrating(q).efficiency;
    q.polarization = GratingPolarization::Unpolarized;
    const double u = solveRcwaGrating(q).efficiency;
    QVERIFY(std::abs(s - p) > 1e-3);  // p couples by cos 2θ_B
    QVERIFY(std::abs(u - 0.5 * (s + p)) < 1e-14);
  }

  // absorption_per_mm is the intensity coefficient: with n1 = 0, T = exp(−α d / cos θ).
  void absorption() {
    RcwaGratingRequest q = transmissionOnBragg();
    q.n1 = 0.0;
    q.absorption_per_mm = 20.0;
    const RcwaGratingAnswer a = solveRcwaGrating(q);
    const double expected = std::exp(-20.0 * 0.020 / std::cos(q.probe_deg * kPi / 180));
    QVERIFY2(std::abs(a.total_efficiency - expected) < 1e-6, qPrintable(QString::number(a.total_efficiency)));
  }

  void badInput() {
    RcwaGratingRequest q = transmissionOnBragg();
    q.probe_deg = 60;
    q.n_cover = 1.0;  // 1.5 sin 60° > 1: the cover cannot launch this probe
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, solveRcwaGrating(q));
    q = transmissionOnBragg();
    q.orders = -1;
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, solveRcwaGrating(q));
    q = transmissionOnBragg();
    q.n_substrate = -1.0;
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, solveRcwaGrating(q));
  }
};

QTEST_GUILESS_MAIN(TestRcwaGrating)

}  // namespace tst_rcwa_grating
#include "tst_rcwa_grating.moc"

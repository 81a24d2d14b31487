// The Kogelnik-vs-RCWA error map: Kogelnik agrees where ρ ≫ 1 and visibly fails where ρ ≲ 1;
// every RCWA point conserves energy and converged; the detuning solver hits its ξ.
#include <QtTest>

#include <cmath>

#include "model/rigorous/kogelnik_vs_rcwa.h"

namespace tst_rcwa_error_map {

using namespace fovea::rigorous;

class TestRcwaErrorMap : public QObject {
  Q_OBJECT
 private slots:
  void quickMap() {
    KogelnikRcwaGrid g = KogelnikRcwaGrid::quick();
    g.kogelnik_repeats = 1;
    const auto pts = kogelnikVsRcwa(g);
    QCOMPARE(int(pts.size()), 3 * 2 * 2 * 2);
    double worst_bragg = 0.0, worst_thin = 0.0;
    for (const auto& p : pts) {
      QVERIFY(p.rcwa_converged);
      QVERIFY2(std::abs(p.rcwa_total - 1.0) < 1e-9, qPrintable(p.geometry.c_str()));
      QVERIFY(std::abs(p.kogelnik.xi - p.xi_target) < 1e-6 * (1 + p.xi_target));
      if (p.rho > 100) worst_bragg = std::max(worst_bragg, p.abs_error);
      if (p.rho < 1) worst_thin = std::max(worst_thin, p.abs_error);
    }
    QVERIFY2(worst_bragg < 2e-2, qPrintable(QString::number(worst_bragg)));
    QVERIFY2(worst_thin > 0.1, qPrintable(QString::number(worst_thin)));
    const auto rows = summariseByRho(pts);
    QVERIFY(rows.size() >= 2);
    QVERIFY(rows.front().max_error > rows.back().max_error);
    const std::string md = kogelnikVsRcwaMarkdown(pts);
    QVERIFY(md.find("| ρ range |") != std::string::npos);
  }
};

QTEST_GUILESS_MAIN(TestRcwaErrorMap)

}  // namespace tst_rcwa_error_map
#include "tst_rcwa_error_map.moc"

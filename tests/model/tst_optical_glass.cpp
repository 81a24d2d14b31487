// The lens catalogue's glasses: Sellmeier indices against the makers' printed n_d and V_d,
// the catalogue's glass names, and the error for a glass the catalogue does not know.
#include <QtTest>

#include <cmath>
#include <string>

#include "model/analysis/lens_catalog.h"
#include "model/analysis/optical_glass.h"

namespace tst_optical_glass {

using namespace fovea;

class TestOpticalGlass : public QObject {
  Q_OBJECT
 private slots:
  void indexAndAbbeNumberMatchTheDataSheets_data() {
    QTest::addColumn<QString>("glass");
    QTest::addColumn<double>("n_d");
    QTest::addColumn<int>("n_d_digits");
    QTest::addColumn<double>("v_d");
    // SCHOTT data sheets (n_d to 5 decimals, V_d to 2); fused silica: Malitson 1965 via the
    // Thorlabs UVFS specification (n 1.4585, V_d 67.82).
    QTest::newRow("N-BK7") << "N-BK7" << 1.51680 << 5 << 64.17;
    QTest::newRow("N-SF11") << "N-SF11" << 1.78472 << 5 << 25.68;
    QTest::newRow("N-SF5") << "N-SF5" << 1.67271 << 5 << 32.25;
    QTest::newRow("N-LAK22") << "N-LAK22" << 1.65113 << 5 << 55.89;
    QTest::newRow("UVFS") << "UVFS" << 1.4585 << 4 << 67.82;
  }
  void indexAndAbbeNumberMatchTheDataSheets() {
    QFETCH(QString, glass);
    QFETCH(double, n_d);
    QFETCH(int, n_d_digits);
    QFETCH(double, v_d);
    const OpticalGlass& g = findOpticalGlass(glass.toStdString());
    const double n = refractiveIndex(g, kFraunhoferDNm);
    const double v = abbeNumberD(g);
    // tolerance = half a unit of the last printed digit
    QVERIFY2(std::abs(n - n_d) <= 0.5 * std::pow(10.0, -n_d_digits), qPrintable(QString::number(n, 'f', 6)));
    QVERIFY2(std::abs(v - v_d) <= 0.005, qPrintable(QString::number(v, 'f', 3)));
    QCOMPARE(glassIndex(g.name, 532.0), refractiveIndex(g, 532.0));
  }

  void indicesAtOtherLinesMatchThePublishedTables() {
    // SCHOTT N-BK7: n_F 1.52238, n_C 1.51432, n_e 1.51872, n(632.8) 1.51509, n_g 1.52668.
    const OpticalGlass& bk7 = findOpticalGlass("N-BK7");
    const std::pair<double, double> bk7_lines[] = {
        {486.1327, 1.52238}, {656.2725, 1.51432}, {546.074, 1.51872}, {632.8, 1.51509}, {435.8343, 1.52668}};
    for (const auto& [lambda, n] : bk7_lines)
      QVERIFY2(std::abs(refractiveIndex(bk7, lambda) - n) <= 5e-6, qPrintable(QString::number(lambda)));
    // Malitson 1965, Table: fused silica n(632.8 nm) 1.45702.
    QVERIFY(std::abs(refractiveIndex(findOpticalGlass("UVFS"), 632.8) - 1.45702) <= 5e-6);
  }

  void dispersionOrdersTheGlasses() {
    // At each laser line of the prototype the flints disperse most: n(460) - n(660) grows as
    // V_d falls (UVFS 67.8 > N-BK7 64.2 > N-LAK22 55.9 > N-SF5 32.3 > N-SF11 25.7).
    double previous = 0;
    for (const char* name : {"UVFS", "N-BK7", "N-LAK22", "N-SF5", "N-SF11"}) {
      const OpticalGlass& g = findOpticalGlass(name);
      const double spread = refractiveIndex(g, 460.0) - refractiveIndex(g, 660.0);
      QVERIFY2(spread > previous, name);
      QVERIFY(refractiveIndex(g, 460.0) > refractiveIndex(g, 532.0));
      QVERIFY(refractiveIndex(g, 532.0) > refractiveIndex(g, 660.0));
      previous = spread;
    }
  }

  void unknownGlassIsAnErrorNamingIt() {
    try {
      (void)findOpticalGlass("BK7");
      QFAIL("accepted an unknown glass");
    } catch (const UnknownGlassError& e) {
      const std::string what = e.what();
      QVERIFY2(what.find("\"BK7\"") != std::string::npos && what.find("N-BK7") != std::string::npos, e.what());
    }
    QVERIFY_THROWS_EXCEPTION(UnknownGlassError, (void)glassIndex("N-FK51A", 532.0));
    try {
      parseLensCatalog(R"({"lenses":[{"part":"X","focal_length_mm":50,"diameter_mm":10,"glass":"N-FK51A"}]})",
                       "mine.json");
      QFAIL("accepted an unknown glass");
    } catch (const LensCatalogError& e) {
      QVERIFY2(std::string(e.what()).find("mine.json: lenses[0].glass: unknown glass \"N-FK51A\"") != std::string::npos,
               e.what());
    }
    try {
      parseLensCatalog(R"({"lenses":[{"part":"X","focal_length_mm":50,"diameter_mm":10}]})", "mine.json");
      QFAIL("accepted a lens without a glass");
    } catch (const LensCatalogError& e) {
      QVERIFY2(std::string(e.what()).find("mine.json: lenses[0].glass: missing") != std::string::npos, e.what());
    }
  }

  void catalogueLensesListTheirRealGlass() {
    // Thorlabs' numbering: LA1xxx / LB1xxx are N-BK7, LA4xxx UV fused silica.
    int uvfs = 0;
    for (const StockLens& l : defaultLensCatalog()) {
      const std::string series = l.part.substr(0, 3);
      if (series == "LA1" || series == "LB1") {
        QCOMPARE(l.glass, std::string("N-BK7"));
      } else if (series == "LA4") {
        QCOMPARE(l.glass, std::string("UVFS"));
        ++uvfs;
      } else {
        QFAIL(qPrintable(QString::fromStdString("unexpected part " + l.part)));
      }
    }
    QCOMPARE(uvfs, 3);
  }
};

QTEST_APPLESS_MAIN(TestOpticalGlass)

}  // namespace tst_optical_glass
#include "tst_optical_glass.moc"

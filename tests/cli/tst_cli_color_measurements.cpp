// fovea-cli color-calibrate --measurements READINGS.csv: spectroradiometer readings (display,
// channel, level, x, y, Y, repeat) -> calibration file, LUT keys and the dE00 report; bad
// rows named by line with exit 1 and no calibration written.
#include <QtTest>

#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

#include "tests/cli/cli_process.h"
#include "tests/test_files.h"

namespace tst_cli_color_measurements {

namespace {
using Run = fovea::testing::CliOutput;
Run cli(const QStringList& args) {
  return fovea::testing::runFoveaCli(args, 60000);
}
QString tmp(const char* name) {
  return QString::fromStdString((fovea::testing::testTmpDir("") / (std::string("cli_colormeas_") + name)).string());
}
enum class Values { Chromaticity, Tristimulus };
// Two repeats of noiseless readings of gamma-2.2 / 2.5 displays: x,y,Y or the same colours as
// tristimulus X,Y,Z (X = x / y Y, Z = (1 - x - y) / y Y).
QString writeReadings(const char* name, const std::string& corrupt_line = {}, Values values = Values::Chromaticity,
                      const std::string& header = {}) {
  const QString path = tmp(name);
  std::ofstream out(path.toStdString());
  out.precision(17);
  const bool xyz = values == Values::Tristimulus;
  out << (!header.empty() ? header
          : xyz           ? std::string("display,channel,level,X,Y,Z,repeat")
                          : std::string("display,channel,level,x,y,Y,repeat"))
      << "\n";
  const double xy[2][3][2] = {{{0.64, 0.33}, {0.265, 0.69}, {0.15, 0.06}},
                              {{0.72, 0.28}, {0.25, 0.68}, {0.145, 0.035}}};
  const double peak[2][3] = {{60, 180, 15}, {35, 120, 9}};
  const char* d[2] = {"foveal", "peripheral"};
  const char* c[3] = {"R", "G", "B"};
  int line = 1;
  for (int i = 0; i < 2; ++i)
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < 256; ++l)
        for (int r = 0; r < 2; ++r) {
          ++line;
          if (line == 40 && !corrupt_line.empty()) {
            out << corrupt_line << "\n";
            continue;
          }
          const double Y = peak[i][k] * std::pow(l / 255.0, i == 0 ? 2.2 : 2.5);
          const double x = xy[i][k][0], y = xy[i][k][1];
          if (xyz)
            out << d[i] << "," << c[k] << "," << l << "," << x / y * Y << "," << Y << "," << (1 - x - y) / y * Y << ","
                << r << "\n";
          else
            out << d[i] << "," << c[k] << "," << l << "," << x << "," << y << "," << Y << "," << r << "\n";
        }
  return path;
}
}  // namespace

class TestCliColorMeasurements : public QObject {
  Q_OBJECT
 private slots:
  void calibratesFromReadings() {
    const QString cal = tmp("cal.json");
    QFile::remove(cal);
    const Run r = cli({"color-calibrate", "--measurements", writeReadings("good.csv"), "--out", cal, "--json"});
    QVERIFY2(r.code == 0, r.err.constData());
    const auto j = nlohmann::json::parse(r.out.toStdString());
    QCOMPARE(j["measurements_csv"]["readings"].get<int>(), 2 * 3 * 256 * 2);
    QCOMPARE(j["measurements_csv"]["repeats_min"].get<int>(), 2);
    // The existing keys, unchanged: dE00 report, fitted gammas, common primaries.
    QVERIFY(j["delta_e00"]["mean"].get<double>() < 1.0);
    QVERIFY(std::abs(j["measured_gamma"]["foveal"]["G"].get<double>() - 2.2) < 0.02);
    QVERIFY(std::abs(j["measured_gamma"]["peripheral"]["R"].get<double>() - 2.5) < 0.02);
    QVERIFY(j["common_primaries_xy"]["R"].is_array());
    QVERIFY(QFile::exists(cal));
    // The calibration file embeds the averaged curves: color-map can use it.
    std::ifstream in(cal.toStdString());
    const auto file = nlohmann::json::parse(in);
    QVERIFY(file.contains("measurements"));
  }

  // Issue 28: X, Y, Z readings give the calibration of the same colours as x, y, Y; an "X"
  // column is never read as the chromaticity x (it was, and the primaries came out wrong).
  void tristimulusReadingsAreTristimulus() {
    const QString cal_xy = tmp("cal-xy.json"), cal_xyz = tmp("cal-xyz.json");
    const Run a = cli({"color-calibrate", "--measurements", writeReadings("xyY.csv"), "--out", cal_xy, "--json"});
    QVERIFY2(a.code == 0, a.err.constData());
    const Run b = cli({"color-calibrate", "--measurements", writeReadings("XYZ.csv", {}, Values::Tristimulus), "--out",
                       cal_xyz, "--json"});
    QVERIFY2(b.code == 0, b.err.constData());
    const auto ja = nlohmann::json::parse(a.out.toStdString()), jb = nlohmann::json::parse(b.out.toStdString());
    QCOMPARE(jb["measurements_csv"]["values"].get<std::string>(), std::string("tristimulus X,Y,Z"));
    QCOMPARE(ja["measurements_csv"]["values"].get<std::string>(), std::string("chromaticity x,y and luminance Y"));
    for (const char* p : {"R", "G", "B"})
      for (int k = 0; k < 2; ++k) {
        const double va = ja["common_primaries_xy"][p][k].get<double>(),
                     vb = jb["common_primaries_xy"][p][k].get<double>();
        QVERIFY2(std::abs(va - vb) < 1e-9, qPrintable(QString("%1[%2]: %3 vs %4").arg(p).arg(k).arg(va).arg(vb)));
      }
    QCOMPARE(jb["common_primaries_xy"]["R"][0].get<double>(), 0.64);  // the foveal red (inside the peripheral one)
    QVERIFY(std::abs(jb["delta_e00"]["mean"].get<double>() - ja["delta_e00"]["mean"].get<double>()) < 1e-9);
    // X with x's other columns (y, Y): refused naming the X column, nothing written.
    const QString cal_bad = tmp("cal-bad.json");
    QFile::remove(cal_bad);
    const Run c = cli({"color-calibrate", "--measurements",
                       writeReadings("Xy.csv", {}, Values::Chromaticity, "display,channel,level,X,y,Y,repeat"), "--out",
                       cal_bad});
    QCOMPARE(c.code, 1);
    QVERIFY2(c.err.contains("Xy.csv:1: the header has the tristimulus column(s) X but lacks Z"), c.err.constData());
    QVERIFY2(c.err.contains("X is not the chromaticity x"), c.err.constData());
    QVERIFY(!QFile::exists(cal_bad));
  }

  // A spreadsheet's UTF-8 byte order mark is accepted; all-zero luminance is refused by channel.
  void bomAcceptedAndDarkRefused() {
    const QString plain = writeReadings("plain.csv");
    QFile in(plain);
    QVERIFY(in.open(QIODevice::ReadOnly));
    const QString bom = tmp("bom.csv");
    {
      QFile out(bom);
      QVERIFY(out.open(QIODevice::WriteOnly | QIODevice::Truncate));
      out.write("\xEF\xBB\xBF" + in.readAll());
    }
    const Run r = cli({"color-calibrate", "--measurements", bom, "--out", tmp("cal-bom.json"), "--json"});
    QVERIFY2(r.code == 0, r.err.constData());
    QCOMPARE(nlohmann::json::parse(r.out.toStdString())["measurements_csv"]["readings"].get<int>(), 3072);
    const QString dark = tmp("dark.csv");
    {
      std::ofstream out(dark.toStdString());
      out << "display,channel,level,x,y,Y,repeat\n";
      for (const char* d : {"foveal", "peripheral"})
        for (const char* c : {"R", "G", "B"})
          for (int l = 0; l < 256; ++l) out << d << "," << c << "," << l << ",0.3,0.3,0,0\n";
    }
    const QString cal_dark = tmp("cal-dark.json");
    QFile::remove(cal_dark);
    const Run z = cli({"color-calibrate", "--measurements", dark, "--out", cal_dark, "--json"});
    QCOMPARE(z.code, 1);
    QVERIFY2(z.err.contains("6 problem(s) in the measurements"), z.err.constData());
    QVERIFY2(z.err.contains("dark.csv: foveal R: the luminance does not rise"), z.err.constData());
    QVERIFY(z.out.isEmpty());  // no dE00 null printed
    QVERIFY(!QFile::exists(cal_dark));
  }

  void badRowsByLineAndNothingWritten() {
    const QString cal = tmp("bad-cal.json");
    QFile::remove(cal);
    const Run r = cli(
        {"color-calibrate", "--measurements", writeReadings("bad.csv", "foveal,R,19,0.64,0.33,-2,0"), "--out", cal});
    QCOMPARE(r.code, 1);
    QVERIFY2(r.err.contains("bad.csv:40: negative luminance Y = -2"), r.err.constData());
    // Level 19 keeps its other repeat, so the row is the only problem.
    QVERIFY2(r.err.contains("1 problem(s) in the measurements, nothing calibrated"), r.err.constData());
    QVERIFY(!QFile::exists(cal));
    // Exactly one of the JSON measurements and the CSV.
    QCOMPARE(cli({"color-calibrate", "--out", cal}).code, 2);
  }
};

QTEST_GUILESS_MAIN(TestCliColorMeasurements)

}  // namespace tst_cli_color_measurements
#include "tst_cli_color_measurements.moc"

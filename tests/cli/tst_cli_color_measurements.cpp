// fovea-cli color-calibrate --measurements READINGS.csv: spectroradiometer readings (display,
// channel, level, x, y, Y, repeat) -> calibration file, LUT keys and the dE00 report; bad
// rows named by line with exit 1 and no calibration written.
#include <QtTest>

#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

#include "tests/cli/cli_process.h"
#include "tests/test_files.h"

namespace {
using Run = fovea::testing::CliOutput;
Run cli(const QStringList& args) {
  return fovea::testing::runFoveaCli(args, 60000);
}
QString tmp(const char* name) {
  return QString::fromStdString((fovea::testing::testTmpDir("") / (std::string("cli_colormeas_") + name)).string());
}
// Two repeats of noiseless readings of gamma-2.2 / 2.5 displays.
QString writeReadings(const char* name, const std::string& corrupt_line = {}) {
  const QString path = tmp(name);
  std::ofstream out(path.toStdString());
  out << "display,channel,level,x,y,Y,repeat\n";
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
          out << d[i] << "," << c[k] << "," << l << "," << xy[i][k][0] << "," << xy[i][k][1] << ","
              << peak[i][k] * std::pow(l / 255.0, i == 0 ? 2.2 : 2.5) << "," << r << "\n";
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
#include "tst_cli_color_measurements.moc"

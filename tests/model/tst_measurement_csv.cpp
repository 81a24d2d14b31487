// Spectroradiometer CSV import (seed B.2.2: primaries and 256 levels per channel, repeated):
// averaging over repeats recovers the curves within the noise, the primaries come from the
// level-255 readings, the calibration built from the CSV matches the one built from the
// exact curves, and every bad row is reported with its line.
#include <QtTest>

#include <cmath>
#include <random>
#include <sstream>

#include "model/color/measurement_csv.h"

namespace tst_measurement_csv {

using namespace fovea::color;

namespace {
struct Channel {
  Xy xy;
  double peak, gamma;
  double at(int level) const { return peak * std::pow(level / 255.0, gamma); }
};
// The two displays of tst_color_calibration (micro-OLED; laser projector through the HOE).
const std::array<std::array<Channel, 3>, 2> kDisplays{{
    {{{{0.640, 0.330}, 60.0, 2.2}, {{0.265, 0.690}, 180.0, 2.2}, {{0.150, 0.060}, 15.0, 2.2}}},
    {{{{0.720, 0.280}, 35.0, 2.6}, {{0.250, 0.680}, 120.0, 2.4}, {{0.145, 0.035}, 9.0, 2.5}}},
}};
const char* kDisplayName[2] = {"foveal", "peripheral"};
const char* kChannelName[3] = {"R", "G", "B"};

// Readings with 1 % multiplicative noise on Y and 0.001 on x, y; `repeats` per level.
std::string csv(int repeats, unsigned seed, double noise = 0.01) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0.0, 1.0);
  std::ostringstream s;
  s << "display,channel,level,x,y,Y,repeat,timestamp\n";
  s.precision(9);
  for (int d = 0; d < 2; ++d)
    for (int c = 0; c < 3; ++c)
      for (int l = 0; l < 256; ++l)
        for (int r = 0; r < repeats; ++r) {
          const Channel& ch = kDisplays[d][c];
          const double Y = std::max(0.0, ch.at(l) * (1 + noise * n(rng)));
          s << kDisplayName[d] << "," << kChannelName[c] << "," << l << "," << ch.xy.x + 0.1 * noise * n(rng) << ","
            << ch.xy.y + 0.1 * noise * n(rng) << "," << Y << "," << r << ",12:00\n";
        }
  return s.str();
}

ColorMeasurements exact() {
  ColorMeasurements m;
  for (int d = 0; d < 2; ++d) {
    DisplayMeasurement& dm = d == 0 ? m.foveal : m.peripheral;
    for (int c = 0; c < 3; ++c) {
      dm.channels[c].xy = kDisplays[d][c].xy;
      for (int l = 0; l < 256; ++l) dm.channels[c].Y.push_back(kDisplays[d][c].at(l));
    }
  }
  return m;
}
}  // namespace

class TestMeasurementCsv : public QObject {
  Q_OBJECT
 private slots:
  void averagesRepeatsIntoCurvesAndPrimaries() {
    const MeasurementImport m = importSpectroradiometerCsv(csv(10, 7));
    QVERIFY2(m.ok(), formatProblems(m, "csv").c_str());
    QCOMPARE(m.rows, 2 * 3 * 256 * 10);
    QCOMPARE(m.min_repeats, 10);
    QCOMPARE(m.max_repeats, 10);
    // Mean of 10 readings with 1 % noise: within 4 sigma / sqrt(10) = 1.3 % of the truth.
    const auto& g = m.measurements.foveal.channels[1];
    for (int l : {64, 128, 200, 255}) {
      const double truth = kDisplays[0][1].at(l);
      QVERIFY2(std::abs(g.Y[l] - truth) < 0.013 * truth, qPrintable(QString::number(g.Y[l] / truth)));
    }
    QCOMPARE(g.Y[0], 0.0);
    // Primaries from the level-255 readings: x noise 0.001 / sqrt(10).
    const auto& b = m.measurements.peripheral.channels[2];
    QVERIFY(std::abs(b.xy.x - 0.145) < 0.0015 && std::abs(b.xy.y - 0.035) < 0.0015);
  }

  void calibrationFromReadingsMatchesTheExactCurves() {
    const MeasurementImport m = importSpectroradiometerCsv(csv(10, 11));
    QVERIFY(m.ok());
    const ColorCalibration from_csv = calibrateColor(m.measurements);
    const ColorCalibration reference = calibrateColor(exact());
    for (int c = 0; c < 3; ++c) {
      QVERIFY(std::abs(from_csv.common[c].x - reference.common[c].x) < 0.003);
      QVERIFY(std::abs(from_csv.common[c].y - reference.common[c].y) < 0.003);
    }
    QVERIFY(std::abs(from_csv.max_luminance - reference.max_luminance) < 0.02 * reference.max_luminance);
    // The two displays still agree through the averaged LUTs: dE00 of the 8-bit drive stays
    // small (quantisation alone gives ~0.3 mean on the exact curves).
    const DeltaEReport r = deltaEBetweenDisplays(from_csv, 5);
    QCOMPARE(r.targets, 125);
    QVERIFY2(r.mean < 1.0 && r.max < 3.0, qPrintable(QString("mean %1 max %2").arg(r.mean).arg(r.max)));
  }

  void badRowsReportedByLine() {
    std::string text = csv(1, 3, 0.0);
    // Line 2 is foveal R level 0; corrupt lines 3, 5 and 7 and drop level 9 of foveal R (line 11).
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    lines[2] = "foveal,R,1,0.64,0.33,abc,0,x";
    lines[4] = "foveal,R,3,0.64,0.33,-0.5,0,x";
    lines[6] = "foveal,Q,5,0.64,1.33,0.5,0,x";
    lines[10] = "# level 9 not measured";
    lines.push_back("foveal,R,255,0.64,0.33,60,0");  // duplicate of an earlier reading
    lines.push_back("peripheral,G,17");              // too few columns
    std::string joined;
    for (const auto& l : lines) joined += l + "\n";
    const MeasurementImport m = importSpectroradiometerCsv(joined);
    QVERIFY(!m.ok());
    const std::string report = formatProblems(m, "readings.csv", 100);
    for (const char* expected : {
             "readings.csv:3: Y 'abc' is not a number",
             "readings.csv:5: negative luminance Y = -0.5",
             "readings.csv:7: channel 'Q' is not R, G or B; y '1.33' is not a number in [0, 1]",
             "readings.csv:1538: duplicate reading (same display, channel, level and repeat as line 257)",
             "readings.csv:1539: expected 7 columns, got 3",
             "readings.csv: foveal R: no readings for levels 1, 3, 5, 9",
         })
      QVERIFY2(report.find(expected) != std::string::npos, (std::string(expected) + "\n--- got:\n" + report).c_str());
    QCOMPARE(m.problems.size(), std::size_t{6});
  }

  void headerAndEmptyFile() {
    MeasurementImport m = importSpectroradiometerCsv("display,channel,level,x,Y\nfoveal,R,0,0.3,0\n");
    QCOMPARE(m.problems.size(), std::size_t{1});
    QVERIFY2(m.problems[0].message.find("lacks the column(s) y, repeat") != std::string::npos,
             m.problems[0].message.c_str());
    QCOMPARE(m.problems[0].line, 1);
    m = importSpectroradiometerCsv("\n# nothing\n");
    QVERIFY(!m.ok());
    QVERIFY(m.problems[0].message.find("no header") != std::string::npos);
  }
};

QTEST_GUILESS_MAIN(TestMeasurementCsv)

}  // namespace tst_measurement_csv
#include "tst_measurement_csv.moc"

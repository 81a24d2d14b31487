// Numeric options are validated before any work, by the analysis registry's one validator
// (model/analysis/analysis_parameters.h): NaN, infinities, values out of their physical
// range and studies with too many samples are refused with exit 2 and a message naming
// the flag and the value.
#include <QtTest>

#include <nlohmann/json.hpp>

#include "tests/cli/cli_process.h"

namespace tst_cli_numeric_options {

namespace {
using Run = fovea::testing::CliOutput;
Run cli(const QStringList& args) {
  fovea::testing::CliCall call;
  call.timeout_ms = 30000;  // every refusal is immediate; a study that starts would hit this
  call.env.insert("FOVEA_CACHE_DIR", qEnvironmentVariable("FOVEA_TEST_TMP", "/tmp") + "/cli_numeric_cache");
  return fovea::testing::runFoveaCli(args, call);
}
}  // namespace

class TestCliNumericOptions : public QObject {
  Q_OBJECT
 private slots:
  void refusals_data() {
    QTest::addColumn<QStringList>("args");
    QTest::addColumn<QString>("message");
    QTest::newRow("sweep tolerance nan") << QStringList{"sweep", "--tolerance-deg", "nan", "--json"}
                                         << "--tolerance-deg: must be a finite number, got nan";
    QTest::newRow("sweep tolerance inf") << QStringList{"sweep", "--tolerance-deg", "inf", "--json"}
                                         << "--tolerance-deg: must be a finite number, got inf";
    QTest::newRow("calibrate noise nan") << QStringList{"calibrate", "geometric", "--virtual",
                                                        "--noise",   "nan",       "--json"}
                                         << "--noise: must be a finite number, got nan";
    QTest::newRow("blend-profile step nan") << QStringList{"blend-profile", "--step-deg", "nan", "--json"}
                                            << "--step-deg: must be a finite number, got nan";
    QTest::newRow("trace gaze 1000") << QStringList{"trace", "-", "--gaze-deg", "1000", "--json"}
                                     << "--gaze-deg: gaze-yaw must lie in [-80, 80] deg, got 1000";
    QTest::newRow("trace gaze pitch -95") << QStringList{"trace", "-", "--gaze-deg", "0,-95", "--json"}
                                          << "--gaze-deg: gaze-pitch must lie in [-80, 80] deg, got -95";
    QTest::newRow("compare-shift step 1e-4") << QStringList{"compare-shift", "--gaze-step", "1e-4", "--json"}
                                             << "--gaze-step: more than 2000 gaze samples (";
    QTest::newRow("compare-shift step 1e-9")
        << QStringList{"compare-shift", "--gaze-step", "1e-9", "--json"} << "--gaze-step: more than 2000 gaze samples";
    QTest::newRow("sweep step 0") << QStringList{"sweep", "--gaze-step", "0", "--json"}
                                  << "--gaze-step: must be > 0 and <= 90 deg, got 0";
    QTest::newRow("sweep reversed range")
        << QStringList{"sweep", "--gaze-from", "10", "--gaze-to", "0", "--json"} << "--gaze-to: must be >= gaze-from";
    QTest::newRow("sensitivity from nan")
        << QStringList{"sensitivity", "--from", "nan", "--json"} << "--from: must be a finite number, got nan";
    QTest::newRow("resolution samples 100.5")
        << QStringList{"resolution", "--samples", "100.5", "--json"} << "--samples: must be a whole number, got 100.5";
    QTest::newRow("selectivity point inf") << QStringList{"selectivity", "--point-mm", "0,inf", "--json"}
                                           << "--point-mm: point-v must be a finite number, got inf";
    QTest::newRow("trace rays text") << QStringList{"trace", "-", "--rays", "many", "--json"}
                                     << "--rays: 'many' is not a number";
  }

  void refusals() {
    QFETCH(QStringList, args);
    QFETCH(QString, message);
    const Run r = cli(args);
    QVERIFY2(r.code == 2, qPrintable(args.join(' ') + " -> " + QString::number(r.code) + ": " + r.err));
    QVERIFY2(r.err.contains(message.toUtf8()), r.err.constData());
    QVERIFY(r.out.isEmpty());  // refused before any work or output
  }

  // The bounds are inclusive: the widest gaze and the most samples still run.
  void boundsThemselvesAreAccepted() {
    Run r = cli({"trace", "-", "--gaze-deg", "80,0", "--rays", "200", "--json"});
    QVERIFY2(r.code == 0, r.err.constData());
    QCOMPARE(nlohmann::json::parse(r.out.toStdString())["gaze_deg"][0].get<double>(), 80.0);
    r = cli({"blend-profile", "--step-deg", "0.25", "--json"});
    QVERIFY2(r.code == 0, r.err.constData());
    QCOMPARE(nlohmann::json::parse(r.out.toStdString())["samples"].size(), std::size_t{41});
  }
};

QTEST_GUILESS_MAIN(TestCliNumericOptions)

}  // namespace tst_cli_numeric_options
#include "tst_cli_numeric_options.moc"

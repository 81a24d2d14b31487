// fovea-cli trace: the issue-4 JSON contract and exit codes.
#include <QtTest>

#include <nlohmann/json.hpp>

namespace {
struct Run {
  int code;
  QByteArray out, err;
};
Run runCli(const QStringList& args) {
  QProcess p;
  p.start(FOVEA_CLI_PATH, args);
  if (!p.waitForStarted()) qFatal("cannot start fovea-cli");
  p.closeWriteChannel();
  p.waitForFinished(120000);
  return {p.exitCode(), p.readAllStandardOutput(), p.readAllStandardError()};
}
QString prototypePath() {
  return QString(FOVEA_SOURCE_DIR) + "/resources/scenes/prototype-bench.json";
}
}  // namespace

class TestCliTrace : public QObject {
  Q_OBJECT
 private slots:
  void jsonContract() {
    const Run r = runCli({"trace", prototypePath(), "--gaze-deg", "0,0", "--rays", "2000", "--json"});
    QVERIFY2(r.code == 0, r.err.constData());
    const auto j = nlohmann::json::parse(r.out.toStdString());
    for (const char* k : {"horizontal", "vertical", "diagonal"}) QVERIFY2(j["fov_deg"].contains(k), k);
    for (const char* k : {"rays", "rays_in_pupil", "rays_efficient", "mean_efficiency"}) QVERIFY2(j.contains(k), k);
    QVERIFY(j["rays_efficient"].get<int>() <= j["rays_in_pupil"].get<int>());
    QVERIFY(j["rays_in_pupil"].get<int>() <= j["rays"].get<int>());
    // The 44 mm plate at 22 mm relief subtends 90 deg; the ray grid resolves a little less.
    const double h = j["fov_deg"]["horizontal"].get<double>();
    QVERIFY2(h > 85.0 && h <= 90.0, qPrintable(QString::number(h)));
    QCOMPARE(j["per_wavelength"].size(), std::size_t{3});
  }

  void overridesAndEmbeddedScene() {
    // '-' is the embedded prototype; one wavelength; a 20 deg gaze needs the HOE shift.
    Run r = runCli({"trace", "-", "--gaze-deg", "20", "--wavelength-nm", "532", "--rays", "1500", "--json"});
    QCOMPARE(r.code, 0);
    auto j = nlohmann::json::parse(r.out.toStdString());
    QCOMPARE(j["rays_in_pupil"].get<int>(), 0);
    QCOMPARE(j["per_wavelength"].size(), std::size_t{1});
    r = runCli({"trace", "-", "--gaze-deg", "20,0", "--hoe-shift-mm", "3.4,0", "--source-shift-mm", "0",
                "--wavelength-nm", "532", "--rays", "1500", "--json"});
    QCOMPARE(r.code, 0);
    j = nlohmann::json::parse(r.out.toStdString());
    QVERIFY(j["fov_deg"]["horizontal"].get<double>() > 80.0);
  }

  void badArgumentsAndInput() {
    const QStringList bad[] = {
        {"trace", "-", "--gaze-deg", "abc", "--json"},     {"trace", "-", "--gaze-deg", "1,2,3", "--json"},
        {"trace", "-", "--rays", "0", "--json"},           {"trace", "-", "--wavelength-nm", "-5", "--json"},
        {"trace", "-", "--hoe-shift-mm", "nan", "--json"}, {"trace", "-", "--polarization", "x", "--json"}};
    const char* named[] = {"--gaze-deg", "--gaze-deg", "--rays", "--wavelength-nm", "--hoe-shift-mm", "--polarization"};
    for (int i = 0; i < 6; ++i) {
      const Run r = runCli(bad[i]);
      QVERIFY2(r.code == 2, qPrintable(bad[i].join(' ')));
      QVERIFY2(r.err.contains(named[i]), r.err.constData());
    }
    QCOMPARE(runCli({"trace", "/nonexistent/scene.json", "--json"}).code, 1);
  }
};

QTEST_GUILESS_MAIN(TestCliTrace)
#include "tst_cli_trace.moc"

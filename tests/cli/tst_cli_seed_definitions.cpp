// fovea-cli: the seed's definitions beside ours on the gaze studies (supplement A.3, A.4, C.2):
// --eyebox-criterion tolerance|centre-fov, --source-shift bench-z|axial (z_s per gaze and the
// gaze coverage), --fov-definition ours|seed; the defaults keep the existing documents.
#include <QtTest>

#include <nlohmann/json.hpp>

#include "tests/cli/cli_process.h"

namespace tst_cli_seed_definitions {

namespace {
using Run = fovea::testing::CliOutput;
Run cli(const QStringList& args) {
  fovea::testing::CliCall call;
  call.timeout_ms = 300000;
  call.env.insert("FOVEA_CACHE_DIR", qEnvironmentVariable("FOVEA_TEST_TMP", "/tmp") + "/cli_seed_definitions_cache");
  return fovea::testing::runFoveaCli(args, call);
}
nlohmann::json parsed(const Run& r) {
  return nlohmann::json::parse(r.out.toStdString());
}
}  // namespace

class TestCliSeedDefinitions : public QObject {
  Q_OBJECT
 private slots:
  void defaultsAreOursAndStated() {
    const Run r = cli({"sweep", "--gaze-from", "0", "--gaze-to", "0", "--gaze-step", "5", "--no-cache", "--json"});
    QCOMPARE(r.code, 0);
    const auto j = parsed(r);
    QCOMPARE(j["eyebox_criterion"].get<std::string>(), std::string("tolerance"));
    QCOMPARE(j["fov_definition"].get<std::string>(), std::string("ours"));
    QCOMPARE(j["source_shift"].get<std::string>(), std::string("bench-z"));
    QCOMPARE(j["method"].get<std::string>(), std::string("hoe"));
    QCOMPARE(j["samples"][0]["source_z_mm"].get<double>(), 0.0);  // the HOE moves, not the source
    QVERIFY(j["samples"][0]["fov_deg"]["horizontal"].get<double>() > 80.0);
  }

  void compareShiftWithTheSeedsSourceAndCriterion() {
    const Run r = cli({"compare-shift", "--gaze-from", "-10", "--gaze-to", "10", "--gaze-step", "10", "--source-shift",
                       "axial", "--eyebox-criterion", "centre-fov", "--no-cache", "--json"});
    QCOMPARE(r.code, 0);
    QVERIFY(r.err.isEmpty());
    const auto j = parsed(r);
    QCOMPARE(j["eyebox_criterion"].get<std::string>(), std::string("centre-fov"));
    QCOMPARE(j["fov_definition"].get<std::string>(), std::string("ours"));
    const auto& src = j["source_shift"];
    QCOMPARE(src["shift_axis"].get<std::string>(), std::string("projector along its optical axis"));
    QCOMPARE(src["gaze_coverage_deg"], src["gaze_range_deg"]);
    QVERIFY(src["gaze_coverage_deg"][0].get<double>() <= 0 && src["gaze_coverage_deg"][1].get<double>() >= 0);
    QCOMPARE(src["samples"].size(), std::size_t{3});
    for (const auto& s : src["samples"]) {
      QVERIFY(s["source_z_mm"].is_number() && std::abs(s["source_z_mm"].get<double>()) <= 10.0);
      QVERIFY(s["fov_deg"].get<double>() > 0);
    }
    QCOMPARE(src["samples"][1]["gaze_deg"].get<double>(), 0.0);
    // Existing keys stay.
    for (const char* k : {"hoe_shift", "source_shift", "static"}) {
      QVERIFY2(j[k]["eyebox_mm"].is_number(), k);
      QVERIFY2(j[k]["travel_mm"].size() == 2, k);
    }
    QVERIFY(j.contains("eyebox_ratio"));
    // The centre-FOV box is never wider than the 3 deg tolerance box of the same study.
    const Run t = cli({"compare-shift", "--gaze-from", "-10", "--gaze-to", "10", "--gaze-step", "10", "--source-shift",
                       "axial", "--no-cache", "--json"});
    QCOMPARE(t.code, 0);
    const auto k = parsed(t);
    QCOMPARE(k["eyebox_criterion"].get<std::string>(), std::string("tolerance"));
    QVERIFY(k["hoe_shift"]["eyebox_mm"].get<double>() >= j["hoe_shift"]["eyebox_mm"].get<double>() - 1e-9);
  }

  void seedFovDefinitionOnSensitivity() {
    const Run r = cli({"sensitivity", "--parameter", "eye.relief_mm", "--from", "22", "--to", "22", "--steps", "1",
                       "--fov-definition", "seed", "--no-cache", "--json"});
    QCOMPARE(r.code, 0);
    const auto j = parsed(r);
    QCOMPARE(j["fov_definition"].get<std::string>(), std::string("seed"));
    const double h = j["samples"][0]["fov_deg"]["horizontal"].get<double>();
    QVERIFY2(h > 80.0 && h <= 90.0 + 1e-6, qPrintable(QString::number(h)));  // the 44 mm plate subtends 90 at 22 mm
  }

  void badDefinitionsAreRefusedByName() {
    const Run a = cli({"sensitivity", "--fov-definition", "seed", "--fov-method", "dense", "--json"});
    QCOMPARE(a.code, 2);
    QVERIFY2(a.err.contains("--fov-definition"), a.err.constData());
    const Run b = cli({"compare-shift", "--eyebox-criterion", "widest", "--json"});
    QCOMPARE(b.code, 2);
    QVERIFY2(b.err.contains("--eyebox-criterion"), b.err.constData());
    const Run c = cli({"sweep", "--source-shift", "lateral", "--json"});
    QCOMPARE(c.code, 2);
    QVERIFY2(c.err.contains("--source-shift"), c.err.constData());
  }
};

QTEST_APPLESS_MAIN(TestCliSeedDefinitions)

}  // namespace tst_cli_seed_definitions
#include "tst_cli_seed_definitions.moc"

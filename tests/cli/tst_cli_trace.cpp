// fovea-cli trace: the JSON contract (docs/physics.md) and exit codes.
#include <QtTest>
#include "tests/test_paths.h"

#include <algorithm>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/cli/cli_process.h"

namespace tst_cli_trace {

namespace {
using Run = fovea::testing::CliOutput;
Run runCli(const QStringList& args) {
  return fovea::testing::runFoveaCli(args);
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

  void statsAndRepeatedGaze() {
    // One --gaze-deg: an object (with --stats, its stats). Several: a list, one result per gaze,
    // each with its own stats; only the first records the HOE.
    Run r = runCli({"trace", "-", "--gaze-deg", "0", "--rays", "1000", "--stats", "--json"});
    QVERIFY2(r.code == 0, r.err.constData());
    auto j = nlohmann::json::parse(r.out.toStdString());
    QVERIFY(j.is_object());
    QVERIFY(j["stats"]["evaluations"].get<long long>() > 0);
    QVERIFY(j["stats"]["stages_recomputed"].is_array());

    r = runCli({"trace", "-", "--gaze-deg", "0", "--gaze-deg", "10,2", "--gaze-deg", "0", "--rays", "1000",
                "--wavelength-nm", "532", "--stats", "--json"});
    QVERIFY2(r.code == 0, r.err.constData());
    j = nlohmann::json::parse(r.out.toStdString());
    QVERIFY(j.is_array());
    QCOMPARE(j.size(), std::size_t{3});
    const auto stages = [&](int i) {
      std::vector<std::string> v;
      for (const auto& s : j[i]["stats"]["stages_recomputed"]) v.push_back(s.get<std::string>());
      return v;
    };
    const auto first = stages(0);
    QVERIFY(std::find(first.begin(), first.end(), "recording:green") != first.end());
    QVERIFY(std::find(first.begin(), first.end(), "coupled_wave:red@532nm") != first.end());
    for (const auto& s : first) QVERIFY2(s.find("660nm") == std::string::npos, s.c_str());  // not asked for
    QCOMPARE(j[0]["stats"]["evaluations"].get<long long>(), 3LL * j[0]["rays_on_hoe"].get<long long>());
    QCOMPARE(stages(1), (std::vector<std::string>{"pupil", "fov", "analyses"}));
    QCOMPARE(j[1]["stats"]["evaluations"].get<long long>(), 0LL);
    QCOMPARE(j[1]["gaze_deg"][0].get<double>(), 10.0);
    QCOMPARE(j[1]["gaze_deg"][1].get<double>(), 2.0);
    for (int i = 0; i < 3; ++i)  // the contract keys in every element
      for (const char* k : {"fov_deg", "rays", "rays_in_pupil", "rays_efficient", "mean_efficiency"})
        QVERIFY2(j[i].contains(k), k);
    QCOMPARE(j[2]["fov_deg"], j[0]["fov_deg"]);
    // Each gaze equals its own single run.
    const Run single =
        runCli({"trace", "-", "--gaze-deg", "10,2", "--rays", "1000", "--wavelength-nm", "532", "--json"});
    const auto js = nlohmann::json::parse(single.out.toStdString());
    QCOMPARE(js["fov_deg"], j[1]["fov_deg"]);
    QCOMPARE(js["mean_efficiency"], j[1]["mean_efficiency"]);
    QVERIFY(!js.contains("stats"));

    // --cull: rays that cannot reach the pupil are not solved (at 20 deg without the HOE shift
    // only a few cross-talk orders cross the pupil); the whole-plate mean is then null.
    r = runCli({"trace", "-", "--gaze-deg", "20", "--gaze-deg", "0", "--rays", "1000", "--cull", "--stats", "--json"});
    QVERIFY2(r.code == 0, r.err.constData());
    j = nlohmann::json::parse(r.out.toStdString());
    QVERIFY(j[0]["stats"]["evaluations"].get<long long>() < 3 * j[0]["rays_on_hoe"].get<long long>() / 5);
    QCOMPARE(j[0]["rays_in_pupil"].get<int>(), 0);
    QVERIFY(j[0]["mean_efficiency_on_hoe"].is_null());
    QVERIFY(j[1]["stats"]["evaluations"].get<long long>() > 0);
    QVERIFY(j[1]["fov_deg"]["horizontal"].get<double>() > 85.0);
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

}  // namespace tst_cli_trace
#include "tst_cli_trace.moc"

// fovea-cli analysis commands: the exact JSON contracts of resolution and optimize-lens,
// argument errors, and the study commands' parameter validation.
#include <QtTest>
#include "tests/test_paths.h"

#include <nlohmann/json.hpp>

#include "tests/cli/cli_process.h"

namespace tst_cli_analyses {

namespace {
using Run = fovea::testing::CliOutput;
Run cli(const QStringList& args) {
  fovea::testing::CliCall call;
  call.env.insert("FOVEA_CACHE_DIR", qEnvironmentVariable("FOVEA_TEST_TMP", "/tmp") + "/cli_analyses_cache");
  return fovea::testing::runFoveaCli(args, call);
}
}  // namespace

class TestCliAnalyses : public QObject {
  Q_OBJECT
 private slots:
  void resolutionContract() {
    const Run r = cli({"resolution", "--gaze-deg", "10", "--json"});
    QCOMPARE(r.code, 0);
    QVERIFY(r.err.isEmpty());  // no progress bar when piped
    const auto j = nlohmann::json::parse(r.out.toStdString());
    QCOMPARE(j["pixels_horizontal"].get<int>(), 1280);
    QVERIFY(j["samples"].size() > 50);
    bool saw_null = false, saw_foveal = false;
    for (const auto& s : j["samples"]) {
      for (const char* k : {"eccentricity_deg", "foveal_cpd", "peripheral_cpd", "optical_limit_cpd", "perceived_cpd"})
        QVERIFY2(s.contains(k), k);
      saw_null |= s["foveal_cpd"].is_null();
      saw_foveal |= s["foveal_cpd"].is_number();
      QVERIFY(s["perceived_cpd"].get<double>() <= 60.0);
    }
    QVERIFY(saw_null && saw_foveal);
    // samples cover the peripheral field
    QCOMPARE(j["samples"].front()["eccentricity_deg"].get<double>(), j["peripheral_field_deg"][0].get<double>());
    QCOMPARE(j["samples"].back()["eccentricity_deg"].get<double>(), j["peripheral_field_deg"][1].get<double>());
  }

  void resolutionRejectsBadGaze() {
    const Run r = cli({"resolution", "--gaze-deg", "abc", "--json"});
    QCOMPARE(r.code, 2);
    QVERIFY(r.err.contains("--gaze-deg"));
  }

  void optimizeLensContract() {
    const Run r = cli({"optimize-lens", "--starts", "1", "--json"});
    QCOMPARE(r.code, 0);
    const auto j = nlohmann::json::parse(r.out.toStdString());
    QVERIFY(j["focal_length_mm"].get<double>() > 0);
    QCOMPARE(j["position_mm"].size(), std::size_t{3});
    QVERIFY(j["tilt_deg"].is_number());
    const double before = j["rms_spot_um"]["before"], after = j["rms_spot_um"]["after"];
    QVERIFY(after < before);
    QVERIFY(std::abs(j["improvement_percent"].get<double>() - 100 * (before - after) / before) < 1e-9);
    // Each candidate's own gain, by the same formula; the best's is the result's.
    bool best_seen = false;
    for (const auto& c : j["candidates"]) {
      const double rms = c["rms_spot_um"];
      QVERIFY(std::abs(c["improvement_percent"].get<double>() - 100 * (before - rms) / before) < 1e-9);
      if (c["part"] == j["part"]) {
        QCOMPARE(c["improvement_percent"].get<double>(), j["improvement_percent"].get<double>());
        best_seen = true;
      }
    }
    QVERIFY(best_seen);
  }

  void optimizeLensIsCachedAndApplies() {
    const QString out = qEnvironmentVariable("FOVEA_TEST_TMP", "/tmp") + "/shaped-scene.json";
    QFile::remove(out);
    const Run a = cli({"optimize-lens", "--starts", "1", "--json", "--no-cache"});
    const Run b = cli({"optimize-lens", "--starts", "1", "--json", "--apply", out});
    QCOMPARE(a.code, 0);
    QCOMPARE(b.code, 0);
    auto ja = nlohmann::json::parse(a.out.toStdString()), jb = nlohmann::json::parse(b.out.toStdString());
    QCOMPARE(ja["cached"].get<bool>(), false);
    QCOMPARE(jb["cached"].get<bool>(), true);  // unchanged scene and parameters: no recomputation
    ja.erase("cached");
    jb.erase("cached");
    QCOMPARE(ja.dump(), jb.dump());
    // The applied scene is valid and carries the lens.
    const Run v = cli({"validate", out, "--json"});
    QCOMPARE(v.code, 0);
    QFile f(out);
    QVERIFY(f.open(QIODevice::ReadOnly));
    const auto scene = nlohmann::json::parse(f.readAll().toStdString());
    QCOMPARE(scene["beam_shaping_lens"]["enabled"].get<bool>(), true);
    QCOMPARE(scene["beam_shaping_lens"]["focal_length_mm"].get<double>(), ja["focal_length_mm"].get<double>());
  }

  void optimizeLensBadCatalogue() {
    const QString bad = qEnvironmentVariable("FOVEA_TEST_TMP", "/tmp") + "/bad_catalog.json";
    QFile f(bad);
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write(R"({"lenses":[{"part":"X","focal_length_mm":"fifty","diameter_mm":10}]})");
    f.close();
    const Run r = cli({"optimize-lens", "--catalog", bad, "--json"});
    QCOMPARE(r.code, 1);
    QVERIFY(r.err.contains("lenses[0].focal_length_mm"));
    QCOMPARE(cli({"optimize-lens", "--catalog", "/nonexistent/c.json"}).code, 1);
  }

  void sensitivityValidatesThePath() {
    Run r = cli({"sensitivity", "--parameter", "eye.no_such", "--from", "1", "--to", "2", "--json"});
    QCOMPARE(r.code, 2);
    QVERIFY(r.err.contains("no_such"));
    r = cli({"sensitivity", "--parameter", "eye.pupil_diameter_mm", "--from", "-1", "--to", "2", "--json"});
    QCOMPARE(r.code, 2);
    QVERIFY(r.err.contains("eye.pupil_diameter_mm"));
  }

  void sweepContract() {
    const QStringList args{"sweep",       "--gaze-from", "-10",    "--gaze-to", "10",
                           "--gaze-step", "10",          "--rays", "1500",      "--json"};
    const Run r = cli(args + QStringList{"--no-cache"});
    QCOMPARE(r.code, 0);
    QVERIFY(r.err.isEmpty());  // no progress bar when piped
    const auto j = nlohmann::json::parse(r.out.toStdString());
    QCOMPARE(j["samples"].size(), std::size_t{3});
    double previous = -1e9;
    for (const auto& s : j["samples"]) {
      QVERIFY(s["gaze_deg"].is_number() && s["hoe_shift_mm"].is_number());
      for (const char* k : {"horizontal", "vertical", "diagonal"}) QVERIFY(s["fov_deg"][k].is_number());
      QVERIFY(s["fov_deg"]["horizontal"].get<double>() > 60);
      QVERIFY(s["hoe_shift_mm"].get<double>() > previous);  // the shift follows the gaze
      previous = s["hoe_shift_mm"].get<double>();
    }
    QCOMPARE(j["samples"][1]["gaze_deg"].get<double>(), 0.0);
    QVERIFY(j["eyebox_mm"].is_number() && j["eyebox_mm"].get<double>() > 0);
    QCOMPARE(j["cached"].get<bool>(), false);
    // The same study again: from the scene-content cache, same numbers.
    const Run again = cli(args);
    QCOMPARE(again.code, 0);
    const auto k = nlohmann::json::parse(again.out.toStdString());
    QCOMPARE(k["cached"].get<bool>(), true);
    QCOMPARE(k["samples"], j["samples"]);
  }

  void compareShiftContract() {
    const Run r = cli({"compare-shift", "--gaze-from", "-30", "--gaze-to", "30", "--gaze-step", "10", "--rays", "1500",
                       "--no-cache", "--json"});
    QCOMPARE(r.code, 0);
    QVERIFY(r.err.isEmpty());
    const auto j = nlohmann::json::parse(r.out.toStdString());
    for (const char* m : {"hoe_shift", "source_shift"}) {
      const auto& e = j[m];
      QVERIFY2(e["gaze_range_deg"].is_array() && e["gaze_range_deg"].size() == 2, m);
      QVERIFY(e["travel_mm"].is_array() && e["travel_mm"].size() == 2);
      QVERIFY(e["eyebox_mm"].is_number() && e["eyebox_mm"].get<double>() > 0);
      QVERIFY(e["gaze_range_deg"][0].get<double>() < 0 && e["gaze_range_deg"][1].get<double>() > 0);
    }
    QVERIFY(j["hoe_shift"]["eyebox_mm"].get<double>() > j["source_shift"]["eyebox_mm"].get<double>());
  }

  void sensitivityContract() {
    const Run r = cli({"sensitivity", "--parameter", "eye.relief_mm", "--from", "20", "--to", "24", "--steps", "3",
                       "--rays", "1500", "--no-cache", "--json"});
    QCOMPARE(r.code, 0);
    QVERIFY(r.err.isEmpty());
    const auto j = nlohmann::json::parse(r.out.toStdString());
    QCOMPARE(j["samples"].size(), std::size_t{3});
    QCOMPARE(j["samples"][1]["value"].get<double>(), 22.0);
    for (const auto& s : j["samples"]) {
      for (const char* k : {"horizontal", "vertical", "diagonal"}) QVERIFY(s["fov_deg"][k].is_number());
      QVERIFY(s["mean_efficiency"].get<double>() > 0 && s["mean_efficiency"].get<double>() <= 1);
    }
  }

  void progressBarOnATerminalOnly() {
    if (!QFile::exists("/usr/bin/script")) QSKIP("util-linux script(1) is needed for a pseudo-terminal");
    // Under script(1) stderr is a terminal: the bar is drawn and reaches 100 %.
    QProcess p;
    QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
    env.insert("FOVEA_CACHE_DIR", qEnvironmentVariable("FOVEA_TEST_TMP", "/tmp") + "/cli_analyses_cache");
    p.setProcessEnvironment(env);
    p.start(
        "/usr/bin/script",
        {"-qec",
         QString("%1 sweep --gaze-from 0 --gaze-to 10 --gaze-step 10 --rays 500 --no-cache --json").arg(FOVEA_CLI_PATH),
         "/dev/null"});
    QVERIFY(p.waitForFinished(120000));
    QCOMPARE(p.exitCode(), 0);
    const QByteArray tty = p.readAllStandardOutput();
    QVERIFY2(tty.contains("sweep [") && tty.contains("100%"), tty.constData());
  }

  void sweepValidatesTheRange() {
    QCOMPARE(cli({"sweep", "--gaze-from", "0", "--gaze-to", "10", "--gaze-step", "0", "--json"}).code, 2);
    QCOMPARE(cli({"sweep", "--gaze-from", "0", "--gaze-to", "10", "--gaze-step", "5", "--axis", "roll", "--json"}).code,
             2);
  }
};

QTEST_GUILESS_MAIN(TestCliAnalyses)

}  // namespace tst_cli_analyses
#include "tst_cli_analyses.moc"

// fovea-cli closed-loop --binocular contract: every key of the issue-30 JSON (fixations,
// summary, latency_budget_ms), a fixation file, usage and input errors, --detector on both eye
// trackers, mode "explicit" running the left eye on its own train; the monocular
// command's keys unchanged beside it (tst_cli_track.cpp).
#include <QtTest>
#include "tests/test_paths.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "model/scene/eye_scene.h"
#include "model/scene/scene_io.h"
#include "tests/cli/cli_process.h"
#include "tests/test_files.h"

namespace tst_cli_binocular {

namespace {
using Run = fovea::testing::CliOutput;
Run cli(const QStringList& args) {
  return fovea::testing::runFoveaCli(args, 300000);
}
std::filesystem::path tmpDir() {
  return fovea::testing::testTmpDir("cli_binocular");
}
const std::string kScene = std::string(FOVEA_SOURCE_DIR) + "/resources/scenes/prototype-bench.json";

void checkContract(const nlohmann::json& j, std::size_t fixations) {
  QVERIFY(j.contains("fixations") && j["fixations"].is_array());
  QCOMPARE(j["fixations"].size(), fixations);
  for (const auto& f : j["fixations"]) {
    for (const char* k :
         {"distance_cm", "direction_deg", "time_to_0_25d_ms", "final_focus_error_d", "inset_on_fovea_fraction"})
      QVERIFY2(f.contains(k), k);
    QVERIFY(f["distance_cm"].is_number());
    QVERIFY(f["direction_deg"].is_array() && f["direction_deg"].size() == 2);
    QVERIFY(f["time_to_0_25d_ms"].is_number() || f["time_to_0_25d_ms"].is_null());
    QVERIFY(f["final_focus_error_d"].is_number());
    for (const char* e : {"left", "right"}) {
      QVERIFY2(f["inset_on_fovea_fraction"].contains(e), e);
      const double v = f["inset_on_fovea_fraction"][e].get<double>();
      QVERIFY(v >= 0 && v <= 1);
    }
  }
  const auto& s = j["summary"];
  for (const char* k : {"fixations", "within_0_25d_fraction", "median_time_to_0_25d_ms"}) QVERIFY2(s.contains(k), k);
  QCOMPARE(s["fixations"].get<std::size_t>(), fixations);
  const double w = s["within_0_25d_fraction"].get<double>();
  QVERIFY(w >= 0 && w <= 1);
  // The extremes over the fixations (docs/gaze-tracking.md's binocular table) are the fixations' own.
  double peak_min = 1e300, peak_max = -1e300, final_max = -1e300, inset_left = 1e300, inset_right = 1e300;
  double time_max = -1e300;
  bool all_settled = true;
  for (const auto& f : j["fixations"]) {
    peak_min = std::min(peak_min, f["peak_focus_error_d"].get<double>());
    peak_max = std::max(peak_max, f["peak_focus_error_d"].get<double>());
    final_max = std::max(final_max, std::abs(f["final_focus_error_d"].get<double>()));
    inset_left = std::min(inset_left, f["inset_on_fovea_fraction"]["left"].get<double>());
    inset_right = std::min(inset_right, f["inset_on_fovea_fraction"]["right"].get<double>());
    if (f["time_to_0_25d_ms"].is_null())
      all_settled = false;
    else
      time_max = std::max(time_max, f["time_to_0_25d_ms"].get<double>());
  }
  QCOMPARE(s["peak_focus_error_d"]["min"].get<double>(), peak_min);
  QCOMPARE(s["peak_focus_error_d"]["max"].get<double>(), peak_max);
  QCOMPARE(s["max_final_focus_error_d"].get<double>(), final_max);
  QCOMPARE(s["min_inset_on_fovea_fraction"]["left"].get<double>(), inset_left);
  QCOMPARE(s["min_inset_on_fovea_fraction"]["right"].get<double>(), inset_right);
  if (all_settled)
    QCOMPARE(s["max_time_to_0_25d_ms"].get<double>(), time_max);
  else
    QVERIFY(s["max_time_to_0_25d_ms"].is_null());
  QVERIFY(s.contains("max_eye_time_to_0_25d_ms"));
  const auto& b = j["latency_budget_ms"];
  QVERIFY(b.is_object());
  for (const char* k : {"capture", "detect", "map", "command", "to_command", "vergence", "focus_to_command",
                        "hoe_motion", "oled_motion", "focus_motion", "paths"})
    QVERIFY2(b.contains(k), k);
  for (const char* k : {"left", "right"}) QVERIFY2(b["hoe_motion"].contains(k) && b["oled_motion"].contains(k), k);
  QVERIFY(std::abs(b["to_command"].get<double>() - (b["capture"].get<double>() + b["detect"].get<double>() +
                                                    b["map"].get<double>() + b["command"].get<double>())) < 1e-9);
  QVERIFY(std::abs(b["focus_to_command"].get<double>() - b["to_command"].get<double>() - b["vergence"].get<double>()) <
          1e-9);
  for (const char* k : {"travel_mm", "range_d", "d_per_mm", "resolution_d_per_count"})
    QVERIFY2(j["focus_stage"].contains(k), k);
  // Per eye, its own train's stages and focus stage (the top-level "focus_stage" is the right eye's).
  for (const char* e : {"left", "right"}) {
    for (const char* k : {"stages", "focus_stage", "focus_motion"}) QVERIFY2(j["eyes"][e].contains(k), k);
    for (const char* k : {"hoe", "foveal_display", "focus"}) QVERIFY2(j["eyes"][e]["stages"][k].is_string(), k);
  }
  QCOMPARE(j["eyes"]["right"]["focus_stage"], j["focus_stage"]);
}
}  // namespace

class TestCliBinocular : public QObject {
  Q_OBJECT

 private slots:
  void usageAndInputErrors() {
    QCOMPARE(cli({"closed-loop", kScene.c_str(), "--fixations", "2"}).code, 2);
    QCOMPARE(cli({"closed-loop", kScene.c_str(), "--binocular"}).code, 2);
    QCOMPARE(cli({"closed-loop", kScene.c_str(), "--binocular", "--fixations", "0"}).code, 2);
    QCOMPARE(cli({"closed-loop", kScene.c_str(), "--binocular", "--fixations", "2", "--latency-sweep", "0"}).code, 2);
    QCOMPARE(cli({"closed-loop", kScene.c_str(), "--binocular", "--fixations", "/nonexistent/f.json"}).code, 1);
    const std::string bad = (tmpDir() / "bad.json").string();
    std::ofstream(bad) << R"({"fixations": [{"distance_cm": 5}]})";
    const Run r = cli({"closed-loop", kScene.c_str(), "--binocular", "--fixations", bad.c_str()});
    QCOMPARE(r.code, 1);
    QVERIFY2(r.err.contains("distance_cm"), r.err.constData());
  }

  void randomFixationsContract() {
    const Run r = cli({"closed-loop", kScene.c_str(), "--binocular", "--fixations", "2", "--seed", "3", "--fps", "60",
                       "--stage-model", "DDSM50", "--json"});
    QVERIFY2(r.code == 0, r.err.constData());
    const auto j = nlohmann::json::parse(r.out.toStdString());
    checkContract(j, 2);
    for (const auto& f : j["fixations"]) {
      QVERIFY(f["distance_cm"].get<double>() >= 30 - 1e-9 && f["distance_cm"].get<double>() <= 250 + 1e-9);
    }
    QCOMPARE(j["stages"]["focus"].get<std::string>(), std::string("DDSM50"));
    QVERIFY(j["vergence"]["samples"].get<int>() > 50);
  }

  void fixationFileContract() {
    const std::string file = (tmpDir() / "fixations.json").string();
    std::ofstream(file) << R"({"fixations": [{"distance_cm": 30, "direction_deg": [5, 0], "hold_ms": 700}]})";
    const Run r = cli({"closed-loop", kScene.c_str(), "--binocular", "--fixations", file.c_str(), "--fps", "60",
                       "--stage-model", "DDSM50", "--json"});
    QVERIFY2(r.code == 0, r.err.constData());
    const auto j = nlohmann::json::parse(r.out.toStdString());
    checkContract(j, 1);
    const auto& f = j["fixations"][0];
    QCOMPARE(f["distance_cm"].get<double>(), 30.0);
    QCOMPARE(f["direction_deg"][0].get<double>(), 5.0);
    QVERIFY(f["time_to_0_25d_ms"].is_number());
    QVERIFY(f["time_to_0_25d_ms"].get<double>() <= 300);
    QVERIFY(std::abs(f["final_focus_error_d"].get<double>()) < 0.25);
  }

  void explicitMirrorTrainGivesTheMirrorDocument() {
    // The binocular example in mode "explicit" with its left train written out from the mirror
    // (explicitBinocularScene): the tracked closed loop's document of mode "mirror", every
    // number but the measured detector wall time, and no warning.
    const std::string mirror = std::string(FOVEA_SOURCE_DIR) + "/resources/scenes/binocular-prototype.json";
    const fovea::SceneLoadResult loaded = fovea::loadSceneFile(mirror);
    QVERIFY(loaded.ok());
    const std::string expl = (tmpDir() / "explicit-mirror.json").string();
    std::ofstream(expl) << fovea::serializeScene(fovea::explicitBinocularScene(*loaded.scene));
    const std::string file = (tmpDir() / "fixation-explicit.json").string();
    std::ofstream(file) << R"({"fixations": [{"distance_cm": 30, "direction_deg": [8, 2], "hold_ms": 600}]})";
    const QStringList common{"--binocular", "--fixations",   file.c_str(), "--fps",
                             "60",          "--stage-model", "DDSM50",     "--json"};
    const Run a = cli(QStringList{"closed-loop", mirror.c_str()} + common);
    const Run b = cli(QStringList{"closed-loop", expl.c_str()} + common);
    QVERIFY2(a.code == 0, a.err.constData());
    QVERIFY2(b.code == 0, b.err.constData());
    QVERIFY2(b.err.isEmpty(), b.err.constData());
    auto ja = nlohmann::json::parse(a.out.toStdString()), jb = nlohmann::json::parse(b.out.toStdString());
    checkContract(jb, 1);
    for (auto* j : {&ja, &jb}) (*j)["latency_budget_ms"].erase("detect_measured_mean");
    QCOMPARE(jb, ja);
    QCOMPARE(jb["eyes"]["left"]["focus_stage"], jb["focus_stage"]);
    // The loop's two tracker calibrations are `calibrate gaze`'s (and the capture wizard's) at
    // the same seed: same eye cameras, same noise (model/gaze/eye_tracker_calibration.h).
    const Run g = cli({"calibrate", "gaze", "--virtual", "--scene", mirror.c_str(), "--json"});
    QVERIFY2(g.code == 0, g.err.constData());
    const auto jg = nlohmann::json::parse(g.out.toStdString());
    for (const char* eye : {"left", "right"}) {
      QCOMPARE(ja["eyes"][eye]["calibration"]["accuracy_deg"].get<double>(),
               jg["eyes"][eye]["accuracy_mean_deg"].get<double>());
      QCOMPARE(ja["eyes"][eye]["calibration"]["precision_deg"].get<double>(),
               jg["eyes"][eye]["precision_rms_s2s_deg"].get<double>());
    }
  }

  void detectorOnBothTrackers() {
    // --detector learned: both eyes' calibrations and trackers use the learned detector. On the
    // classic renderer's frames its calibration accuracy is 0.24/0.24 deg per eye (classical
    // 0.23 deg), the vergence's closed-form SD 0.032 D (classical 0.020 D; earlier networks and
    // flips 0.032-0.052 D). This one fixation's focus ends 0.109 D off, within the 0.25 D target
    // after 50 ms of the 700 ms hold (classical: 0.115 D, 34.5 ms). Earlier networks ended 0.017-0.207 D off, one
    // only after 682 ms (docs/gaze-tracking.md keeps their figures): the end error is the loop's calibration bias,
    // which differs by detector, so the test holds the target, not one detector's figure.
    const std::string file = (tmpDir() / "fixation-detector.json").string();
    std::ofstream(file) << R"({"fixations": [{"distance_cm": 30, "direction_deg": [5, 0], "hold_ms": 700}]})";
    const Run r = cli({"closed-loop", kScene.c_str(), "--binocular", "--fixations", file.c_str(), "--fps", "60",
                       "--stage-model", "DDSM50", "--detector", "learned", "--json"});
    QVERIFY2(r.code == 0, r.err.constData());
    const auto j = nlohmann::json::parse(r.out.toStdString());
    checkContract(j, 1);
    QCOMPARE(j["detector"].get<std::string>(), std::string("learned"));
    for (const char* e : {"left", "right"}) {
      const double accuracy = j["eyes"][e]["calibration"]["accuracy_deg"].get<double>();
      QVERIFY2(accuracy > 0.1 && accuracy < 0.4, qPrintable(QString("%1 %2").arg(e).arg(accuracy)));
      QCOMPARE(j["eyes"][e]["frames"]["tracked"], j["eyes"][e]["frames"]["captured"]);
    }
    const double sigma = j["vergence"]["closed_form_sigma_d"].get<double>();
    QVERIFY2(sigma > 0.025 && sigma < 0.06, qPrintable(QString::number(sigma)));  // classical 0.020 D
    const double final_error = j["fixations"][0]["final_focus_error_d"].get<double>();
    QVERIFY2(std::abs(final_error) < 0.25, qPrintable(QString::number(final_error)));  // the focus target
    const double settle = j["fixations"][0]["time_to_0_25d_ms"].get<double>();
    QVERIFY2(settle > 0 && settle < 700, qPrintable(QString::number(settle)));  // within the 700 ms hold
    // A bad --detector: exit 2; a missing model: exit 1 naming its path, before any frame.
    QCOMPARE(cli({"closed-loop", kScene.c_str(), "--binocular", "--fixations", "1", "--detector", "neural"}).code, 2);
    fovea::testing::CliCall call;
    call.env.insert("FOVEA_PUPIL_MODEL", "/nonexistent/models/pupil-net.onnx");
    const Run missing = fovea::testing::runFoveaCli(
        {"closed-loop", kScene.c_str(), "--binocular", "--fixations", "1", "--detector", "auto"}, call);
    QCOMPARE(missing.code, 1);
    QVERIFY2(missing.err.contains("/nonexistent/models/pupil-net.onnx"), missing.err.constData());
  }
};

QTEST_GUILESS_MAIN(TestCliBinocular)

}  // namespace tst_cli_binocular
#include "tst_cli_binocular.moc"

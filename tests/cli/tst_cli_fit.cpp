// fovea-cli fit and fit-targets: the JSON contract (docs/fitting.md), the synthetic recovery
// through the command line (targets computed by our own forward model from a perturbed
// prototype, fitted from the prototype: each parameter back within its uncertainty, the
// written scene holding the fitted values), and bad input named.
#include <QtTest>
#include "tests/test_paths.h"

#include <QFile>
#include <QTemporaryDir>

#include <cmath>

#include <nlohmann/json.hpp>

#include "cli_process.h"
#include "model/analysis/fit_targets.h"
#include "model/scene/scene_io.h"
#include "model/scene/scene_parameters.h"

namespace tst_cli_fit {

using fovea::testing::runFoveaCli;

namespace {
const QString kScene = QString(FOVEA_SOURCE_DIR) + "/resources/scenes/prototype-bench.json";

QString writeFile(const QTemporaryDir& d, const QString& name, const std::string& text) {
  const QString p = d.filePath(name);
  QFile f(p);
  if (!f.open(QIODevice::WriteOnly)) return {};
  f.write(QByteArray::fromStdString(text));
  return p;
}

// Four targets, one laser each, edge FOV, the HOE unmoved: cheap.
nlohmann::json targetList() {
  return nlohmann::json::parse(R"([
    {"id": "fov-v", "observable": "fov_deg", "shift": "none", "direction": "vertical", "wavelength_nm": 532,
     "value": 0, "sigma": 0.05, "source": "simulated"},
    {"id": "fov-h", "observable": "fov_deg", "shift": "none", "wavelength_nm": 532, "value": 0, "sigma": 0.05},
    {"id": "eff", "observable": "mean_efficiency", "shift": "none", "wavelength_nm": 532, "value": 0, "sigma": 0.002},
    {"id": "spot", "observable": "rms_spot_um", "value": 0, "sigma": 2}
  ])");
}
}  // namespace

class TestCliFit : public QObject {
  Q_OBJECT
 private slots:
  void recoversThroughTheCommandLine() {
    using namespace fovea;
    const Scene nominal = *loadSceneFile(kScene.toStdString()).scene;
    const std::vector<std::pair<std::string, double>> truth{
        {"projector.pixel_beam.waist_fwhm_um", 690}, {"hoe.size_mm[1]", 35.2}, {"hoe_layers[1].n1", 0.0165}};
    Scene built = nominal;
    for (const auto& [path, v] : truth) built = withParameter(built, path, v);
    std::vector<FitTarget> targets = parseFitTargets(targetList());
    const std::vector<double> measured = evaluateTargets(built, targets);
    for (std::size_t i = 0; i < targets.size(); ++i) targets[i].value = measured[i];
    QTemporaryDir dir;
    const QString file = writeFile(dir, "targets.json", fitTargetsJson(targets, "synthetic").dump(2));
    const QString out = dir.filePath("fitted.json");
    const auto r = runFoveaCli({"fit", kScene, "--targets", file, "--free", "projector.pixel_beam.waist_fwhm_um",
                                "hoe.size_mm[1]=30:40", "hoe_layers[1].n1=+-0.004", "--starts", "2", "--seed", "7",
                                "--write-scene", out, "--json"});
    QVERIFY2(r.code == 0, r.err.constData());
    const auto j = nlohmann::json::parse(r.out.toStdString());
    for (const char* k :
         {"algorithm", "starts", "seed", "evaluations", "parameters", "targets", "chi2_initial", "chi2", "dof",
          "reduced_chi2", "covariance_scaled_by_reduced_chi2", "parameter_order", "covariance", "correlation",
          "relative_singular_values", "rcond", "warnings", "start_results", "targets_file"})
      QVERIFY2(j.contains(k), k);
    QCOMPARE(j["algorithm"].get<std::string>(), std::string("LN_BOBYQA"));
    QCOMPARE(j["starts"].get<int>(), 2);
    QCOMPARE(j["seed"].get<int>(), 7);
    QCOMPARE(j["start_results"].size(), std::size_t(2));
    QCOMPARE(j["dof"].get<int>(), 1);
    QVERIFY(j["reduced_chi2"].is_number());
    QVERIFY(j["chi2_initial"].get<double>() > 100);
    QVERIFY(j["chi2"].get<double>() < 0.01);
    QVERIFY(j["warnings"].empty());
    QCOMPARE(j["parameters"][1]["lower"].get<double>(), 30.0);
    QVERIFY(std::abs(j["parameters"][2]["upper"].get<double>() - 0.019) < 1e-12);
    const Scene fitted = *loadSceneFile(out.toStdString()).scene;
    for (std::size_t k = 0; k < truth.size(); ++k) {
      const auto& p = j["parameters"][k];
      QCOMPARE(p["path"].get<std::string>(), truth[k].first);
      for (const char* key : {"unit", "initial", "fitted", "change", "lower", "upper", "uncertainty",
                              "uncertainty_scaled", "determined", "at_bound"})
        QVERIFY2(p.contains(key), key);
      const double sigma = p["uncertainty"].get<double>();
      QVERIFY2(std::abs(p["fitted"].get<double>() - truth[k].second) < sigma, truth[k].first.c_str());
      QVERIFY(sigma < 0.2 * std::abs(truth[k].second - p["initial"].get<double>()));
      QCOMPARE(parameterValue(fitted, truth[k].first), p["fitted"].get<double>());
      QVERIFY(std::abs(j["correlation"][k][k].get<double>() - 1) < 1e-12);
    }
    for (const auto& t : j["targets"])
      for (const char* key : {"id", "observable", "parameters", "unit", "source", "value", "sigma", "initial_model",
                              "model", "residual", "normalised"})
        QVERIFY2(t.contains(key), key);
    QCOMPARE(j["targets"][0]["source"].get<std::string>(), std::string("simulated"));
    QVERIFY(std::abs(j["targets"][3]["normalised"].get<double>()) < 0.1);
  }

  void refusals() {
    QTemporaryDir dir;
    nlohmann::json bad = targetList();
    bad[1]["observable"] = "efficiency";
    const QString badFile = writeFile(dir, "bad.json", bad.dump());
    const QString good = writeFile(dir, "good.json", targetList().dump());
    auto r = runFoveaCli({"fit", kScene, "--targets", badFile, "--free", "eye.relief_mm", "--json"});
    QCOMPARE(r.code, 1);
    QVERIFY2(r.err.contains("unknown observable \"efficiency\"") && r.err.contains("fov_deg, mean_efficiency"),
             r.err.constData());
    r = runFoveaCli({"fit", kScene, "--targets", good, "--free", "eye.colour_mm", "--json"});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("--free") && r.err.contains("eye.colour_mm"), r.err.constData());
    r = runFoveaCli({"fit", kScene, "--targets", good, "--free", "projector.pixels[1]", "--json"});
    QCOMPARE(r.code, 2);
    QVERIFY(r.err.contains("integer field cannot be fitted"));
    r = runFoveaCli({"fit", kScene, "--targets", good, "--free", "eye.relief_mm=40:50", "--json"});
    QCOMPARE(r.code, 2);
    QVERIFY(r.err.contains("outside the bounds"));
    r = runFoveaCli({"fit", kScene, "--free", "eye.relief_mm", "--json"});
    QCOMPARE(r.code, 2);
    QVERIFY(r.err.contains("--targets"));
    r = runFoveaCli({"fit", kScene, "--targets", good, "--free", "eye.relief_mm", "--starts", "0", "--json"});
    QCOMPARE(r.code, 2);
    QVERIFY(r.err.contains("--starts"));
    r = runFoveaCli({"fit", kScene, "--targets", dir.filePath("none.json"), "--free", "eye.relief_mm"});
    QCOMPARE(r.code, 1);
    QVERIFY(r.err.contains("none.json"));
    r = runFoveaCli({"fit", kScene, "--targets", good, "--free", "eye.relief_mm", "--write-scene",
                     dir.filePath("no/such/dir/x.json")});
    QCOMPARE(r.code, 2);
    QVERIFY(r.err.contains("--write-scene"));
  }

  // --targets-select picks ids and groups; a misfit (fov-v 40 sigma off, the free pixel-beam waist
  // cannot move it) gives reduced
  // chi2 > 1, the scaled uncertainties marked as the ones shown and a warning naming it.
  void targetsSelectAndReducedChi2() {
    using namespace fovea;
    const Scene nominal = *loadSceneFile(kScene.toStdString()).scene;
    std::vector<FitTarget> targets = parseFitTargets(targetList());
    const std::vector<double> measured = evaluateTargets(nominal, targets);
    for (std::size_t i = 0; i < targets.size(); ++i) targets[i].value = measured[i];
    targets[0].value += 2.0;  // fov-v: 40 sigma above what the prototype gives
    QTemporaryDir dir;
    const QString file = writeFile(dir, "targets.json", fitTargetsJson(targets, "synthetic").dump(2));
    auto r = runFoveaCli({"fit", kScene, "--targets", file, "--free", "projector.pixel_beam.waist_fwhm_um",
                          "--targets-select", "fov-,spot", "--starts", "1", "--json"});
    QVERIFY2(r.code == 0, r.err.constData());
    auto j = nlohmann::json::parse(r.out.toStdString());
    for (const char* k :
         {"reduced_chi2", "targets_select", "targets_available", "uncertainties_shown", "worst_targets"})
      QVERIFY2(j.contains(k), k);
    QCOMPARE(j["targets"].size(), std::size_t(3));  // fov-v, fov-h, spot; not eff
    QCOMPARE(j["targets"][0]["id"].get<std::string>(), std::string("fov-v"));
    QCOMPARE(j["targets"][2]["id"].get<std::string>(), std::string("spot"));
    QCOMPARE(j["targets_available"].get<int>(), 4);
    QCOMPARE(j["targets_select"].get<std::string>(), std::string("fov-,spot"));
    QCOMPARE(j["dof"].get<int>(), 2);
    const double reduced = j["reduced_chi2"].get<double>();
    QVERIFY(std::abs(reduced - j["chi2"].get<double>() / 2) < 1e-9 * reduced);
    QVERIFY2(reduced > 1, qPrintable(QString::number(reduced)));
    QCOMPARE(j["uncertainties_shown"].get<std::string>(), std::string("scaled"));
    const auto& p = j["parameters"][0];
    QVERIFY(std::abs(p["uncertainty_scaled"].get<double>() - p["uncertainty"].get<double>() * std::sqrt(reduced)) <
            1e-9 * p["uncertainty_scaled"].get<double>());
    QCOMPARE(j["worst_targets"][0]["id"].get<std::string>(), std::string("fov-v"));
    bool warned = false;
    for (const auto& w : j["warnings"])
      warned = warned || (w["message"].get<std::string>().find("reduced chi2") != std::string::npos &&
                          w["message"].get<std::string>().find("fov-v") != std::string::npos);
    QVERIFY2(warned, j["warnings"].dump().c_str());
    // The table for people: the reduced chi2 and the scaled uncertainty.
    r = runFoveaCli({"fit", kScene, "--targets", file, "--free", "projector.pixel_beam.waist_fwhm_um",
                     "--targets-select", "fov-,spot", "--starts", "1"});
    QVERIFY2(r.code == 0, r.err.constData());
    QVERIFY2(r.out.contains("reduced chi2") && r.out.contains("scaled by sqrt(chi2/dof)"), r.out.constData());
    QVERIFY2(r.err.contains("worst targets: fov-v"), r.err.constData());
    // "!" removes; a name that matches nothing is refused with the file's groups.
    r = runFoveaCli({"fit", kScene, "--targets", file, "--free", "projector.pixel_beam.waist_fwhm_um",
                     "--targets-select", "all,!fov-v,!eff", "--starts", "1", "--max-evals", "5", "--json"});
    QVERIFY2(r.code == 0, r.err.constData());
    j = nlohmann::json::parse(r.out.toStdString());
    QCOMPARE(j["targets"].size(), std::size_t(2));
    QCOMPARE(j["targets"][0]["id"].get<std::string>(), std::string("fov-h"));
    r = runFoveaCli({"fit", kScene, "--targets", file, "--free", "hoe.size_mm[1]", "--targets-select", "meas-"});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("--targets-select") && r.err.contains("\"meas-\" matches no target") &&
                 r.err.contains("groups: fov-"),
             r.err.constData());
  }

  void targetsFromACaptureManifest() {
    // A geometric session's manifest as the capture wizard writes it: x_p per gaze from the
    // HOE stage positions of the peripheral captures; the foveal capture adds nothing.
    const nlohmann::json manifest = nlohmann::json::parse(R"js({
      "format": "fovea-capture-session", "version": 1, "kind": "geometric", "scene": "prototype",
      "steps": [
        {"id": "geometric/peripheral/yaw-10", "kind": "geometric", "display": "peripheral", "gaze_deg": [-10, 0],
         "instruction": "", "pattern": {"kind": "checkerboard", "squares": [7, 9], "square_px": 26,
         "origin_px": [500, 240], "dark": 0.05, "light": 0.9, "marker": true}, "targets": []},
        {"id": "geometric/foveal/yaw-10", "kind": "geometric", "display": "foveal", "gaze_deg": [-10, 0],
         "instruction": "", "pattern": {"kind": "checkerboard", "squares": [8, 5], "square_px": 26,
         "origin_px": [500, 240], "dark": 0.05, "light": 0.9, "marker": true}, "targets": []},
        {"id": "geometric/peripheral/pitch+5", "kind": "geometric", "display": "peripheral", "gaze_deg": [0, 5],
         "instruction": "", "pattern": {"kind": "checkerboard", "squares": [7, 9], "square_px": 26,
         "origin_px": [500, 240], "dark": 0.05, "light": 0.9, "marker": true}, "targets": []}],
      "captures": [
        {"step": "geometric/peripheral/yaw-10", "image": "000.png", "positions": {"hoe.x": -1.52, "hoe.y": 0.0}},
        {"step": "geometric/foveal/yaw-10", "image": "001.png", "positions": {"hoe.x": -1.52, "hoe.y": 0.0}},
        {"step": "geometric/peripheral/pitch+5", "image": "002.png", "positions": {"hoe.x": 0.0, "hoe.y": 0.61}}],
      "measurements": []})js");
    QTemporaryDir dir;
    writeFile(dir, "manifest.json", manifest.dump());
    const QString out = dir.filePath("targets.json");
    const auto r = runFoveaCli({"fit-targets", dir.path(), "--sigma-mm", "0.1", "--out", out, "--json"});
    QVERIFY2(r.code == 0, r.err.constData());
    const auto j = nlohmann::json::parse(r.out.toStdString());
    QCOMPARE(j["format"].get<std::string>(), std::string("fovea-fit-targets"));
    QCOMPARE(j["targets"].size(), std::size_t(2));
    const auto& a = j["targets"][0];
    QCOMPARE(a["observable"].get<std::string>(), std::string("x_p_mm"));
    QCOMPARE(a["gaze_deg"].get<double>(), -10.0);
    QCOMPARE(a["axis"].get<std::string>(), std::string("yaw"));
    QCOMPARE(a["value"].get<double>(), -1.52);
    QCOMPARE(a["sigma"].get<double>(), 0.1);
    QCOMPARE(a["source"].get<std::string>(), std::string("bench (geometric/peripheral/yaw-10)"));
    QCOMPARE(j["targets"][1]["axis"].get<std::string>(), std::string("pitch"));
    QCOMPARE(j["targets"][1]["value"].get<double>(), 0.61);
    // The written file is a targets file fit reads.
    QFile f(out);
    QVERIFY(f.open(QIODevice::ReadOnly));
    QCOMPARE(fovea::parseFitTargets(nlohmann::json::parse(f.readAll().toStdString())).size(), std::size_t(2));
    // Not a manifest / no target: named.
    const QString other = writeFile(dir, "other.json", R"({"format": "fovea-scene"})");
    auto e = runFoveaCli({"fit-targets", other, "--json"});
    QCOMPARE(e.code, 1);
    QVERIFY(e.err.contains("not a capture session manifest"));
    nlohmann::json color = manifest;
    color["kind"] = "color";
    e = runFoveaCli({"fit-targets", writeFile(dir, "color.json", color.dump()), "--json"});
    QCOMPARE(e.code, 1);
    QVERIFY2(e.err.contains("no target") && e.err.contains("color session"), e.err.constData());
    QCOMPARE(runFoveaCli({"fit-targets", out, "--sigma-mm", "-1"}).code, 2);
  }
};

QTEST_GUILESS_MAIN(TestCliFit)

}  // namespace tst_cli_fit
#include "tst_cli_fit.moc"

// The paper reproduced (docs/seed-reproduction.md): the seed's targets file parses in the fit
// format with every target marked simulated or measured, the fitted scene
// resources/scenes/seed-fitted.json loads and validates, and our model gives on it the values
// the document's "ours, fitted" column claims (within the tolerances stated there), so that
// the document cannot drift silently from the code.
#include <QtTest>
#include "tests/test_paths.h"

#include <cmath>
#include <map>

#include "model/analysis/fit_targets.h"
#include "model/scene/scene_geometry.h"
#include "model/scene/scene_io.h"
#include "tests/test_files.h"

namespace tst_seed_reproduction {

using namespace fovea;

namespace {
const std::filesystem::path kRoot = FOVEA_SOURCE_DIR;

std::vector<FitTarget> seedTargets() {
  return parseFitTargets(nlohmann::json::parse(testing::readFileText(kRoot / "resources/seed/seed-targets.json")));
}

Scene prototypeScene() {
  SceneLoadResult r = loadSceneFile(kRoot / "resources/scenes/prototype-bench.json");
  if (!r.scene) qFatal("prototype-bench.json does not load");
  return *r.scene;
}

// The projector moved along its line of sight to the HOE centre (the bench origin) to a throw
// of throw_mm, and every layer recorded from there (the "hand step" of seed-fitted.json).
Scene withThrow(Scene s, double throw_mm) {
  auto scaled = [&](Vec3mm& p) {
    const double k = throw_mm / std::hypot(p[0], p[1], p[2]);
    for (double& c : p) c *= k;
  };
  scaled(s.projector.pose.position_mm);
  for (HoeLayer& l : s.hoe_layers) scaled(l.recording.reference_point_mm);
  return s;
}

// The CLI studies' precision (edges to 0.005 deg, 6 bisections).
ObservableSettings cliPrecision() {
  ObservableSettings s;
  s.fov_tolerance_deg = 0.005;
  s.shift_bisections = 6;
  s.border_bisections = 6;
  return s;
}

// One fit observable's value (docs/fitting.md).
double observable(const Scene& scene, const nlohmann::json& target,
                  const ObservableSettings& precision = cliPrecision()) {
  nlohmann::json t = target;
  t["id"] = "t";
  t["value"] = 0;
  t["sigma"] = 1;
  return evaluateTargets(scene, parseFitTargets(nlohmann::json::array({t})), precision).at(0);
}

Scene fittedScene() {
  SceneLoadResult r = loadSceneFile(kRoot / "resources/scenes/seed-fitted.json");
  if (!r.scene) qFatal("seed-fitted.json does not load");
  return *r.scene;
}
}  // namespace

class TestSeedReproduction : public QObject {
  Q_OBJECT
 private slots:
  void targetsAreMarkedSimulatedOrMeasured() {
    const std::vector<FitTarget> targets = seedTargets();
    QCOMPARE(targets.size(), std::size_t{19});
    for (const FitTarget& t : targets) {
      const bool simulated = t.source.find("(simulated)") != std::string::npos;
      const bool measured = t.source.find("(measured") != std::string::npos;
      QVERIFY2(simulated != measured, t.id.c_str());
      QCOMPARE(t.id.rfind(simulated ? "sim-" : "meas-", 0), std::size_t{0});
    }
  }

  void fittedSceneLoadsAndValidates() {
    const SceneLoadResult r = loadSceneFile(kRoot / "resources/scenes/seed-fitted.json");
    QVERIFY(r.scene.has_value());
    QVERIFY2(r.errors.empty() && r.warnings.empty(), r.errors.empty() ? "" : r.errors.front().c_str());
    // From the prototype: the HOE recorded from a 150 mm throw, then the projector and the eye
    // fitted to within a millimetre of that design (docs/seed-reproduction.md).
    const Scene& sc = *r.scene;
    for (const HoeLayer& l : sc.hoe_layers) {
      const auto& q = l.recording.reference_point_mm;
      QVERIFY(std::abs(std::hypot(q[0], q[1], q[2]) - 150.0) < 1e-3);
      QVERIFY((toVec(sc.projector.pose.position_mm) - toVec(q)).norm() < 1.0);
    }
    QVERIFY(std::abs(sc.eye.relief_mm - 22.0) < 1.0);
  }

  void fittedSceneReproducesTheDocumentedValues() {
    // docs/seed-reproduction.md, column "ours, fitted" (fit observables, docs/fitting.md).
    const std::map<std::string, std::pair<double, double>> documented{// id: value, tolerance
                                                                      {"sim-fov-h-0", {90.068, 0.02}},
                                                                      {"sim-xp-0", {0.145, 0.05}},
                                                                      {"sim-fov-h-26.7", {89.531, 0.2}},
                                                                      {"sim-xp-26.7", {3.812, 0.05}},
                                                                      {"sim-fov-h-35.7", {77.251, 0.2}},
                                                                      {"sim-xp-35.7", {5.445, 0.05}},
                                                                      {"sim-xp-m20", {-2.699, 0.05}},
                                                                      {"sim-xp-p20", {2.945, 0.05}},
                                                                      {"sim-eyebox-hoe", {4.753, 0.1}},
                                                                      {"sim-eyebox-source", {3.282, 0.1}},
                                                                      {"sim-coverage-source-lo", {-13.672, 0.2}},
                                                                      {"sim-coverage-source-hi", {2.813, 0.2}},
                                                                      {"sim-travel-source-lo", {6.045, 0.1}},
                                                                      {"sim-travel-source-hi", {-0.986, 0.1}},
                                                                      {"meas-fov-h-0", {90.068, 0.02}},
                                                                      {"meas-fov-v-0", {78.582, 0.05}},
                                                                      {"meas-fov-d-0", {113.686, 0.05}},
                                                                      {"meas-eyebox-h", {10.963, 0.1}},
                                                                      {"meas-eyebox-v", {11.959, 0.1}}};
    const std::vector<FitTarget> targets = seedTargets();
    // The CLI studies' precision (edges to 0.005 deg, 6 bisections): a third of the fitter's
    // cost, within 0.02 of its values.
    const std::vector<double> ours = evaluateTargets(fittedScene(), targets, cliPrecision());
    QCOMPARE(ours.size(), targets.size());
    QString all;
    for (std::size_t i = 0; i < targets.size(); ++i)
      all += QString("%1 %2\n").arg(QString::fromStdString(targets[i].id)).arg(ours[i], 0, 'f', 3);
    for (std::size_t i = 0; i < targets.size(); ++i) {
      const auto it = documented.find(targets[i].id);
      QVERIFY2(it != documented.end(), targets[i].id.c_str());
      QVERIFY2(std::abs(ours[i] - it->second.first) <= it->second.second,
               qPrintable(QString("%1: ours %2, documented %3 +- %4\n%5")
                              .arg(QString::fromStdString(targets[i].id))
                              .arg(ours[i])
                              .arg(it->second.first)
                              .arg(it->second.second)
                              .arg(all)));
    }
  }

  void residualExperimentsGiveTheDocumentedValues() {
    // docs/seed-reproduction.md, "Why the residuals remain": x_p at +20 deg (the plateau's
    // middle) moves little with the throw and the eye relief, and the hand step's HOE eye box
    // (tolerance 3 deg) does not move with the film's thickness. Each value at its printed
    // digits; the eye box at the fitter's own precision (6 border bisections leave it 12.868).
    const nlohmann::json xp20 = {{"observable", "x_p_mm"}, {"gaze_deg", 20.0}, {"unit", "mm"}};
    const Scene proto = prototypeScene();
    const double throw200 = observable(withThrow(proto, 200), xp20);
    QVERIFY2(std::abs(throw200 - 3.09) <= 0.005, qPrintable(QString::number(throw200, 'f', 4)));
    for (const auto& [relief, documented] : {std::pair{20.0, 3.92}, std::pair{25.0, 3.42}}) {
      Scene s = proto;
      s.eye.relief_mm = relief;
      const double xp = observable(s, xp20);
      QVERIFY2(std::abs(xp - documented) <= 0.005,
               qPrintable(QString("relief %1: x_p %2").arg(relief).arg(xp, 0, 'f', 4)));
    }
    const nlohmann::json box = {{"observable", "eyebox_mm"}, {"method", "hoe"}, {"tolerance_deg", 3.0}, {"unit", "mm"}};
    for (const double thickness : {16.0, 20.0, 25.0, 30.0}) {
      Scene s = withThrow(proto, 150);
      for (HoeLayer& l : s.hoe_layers) l.thickness_um = thickness;
      const double eyebox = observable(s, box, ObservableSettings{});
      QVERIFY2(std::abs(eyebox - 12.88) <= 0.005,
               qPrintable(QString("%1 um: eye box %2 mm").arg(thickness).arg(eyebox, 0, 'f', 4)));
    }
  }
};

QTEST_APPLESS_MAIN(TestSeedReproduction)

}  // namespace tst_seed_reproduction
#include "tst_seed_reproduction.moc"

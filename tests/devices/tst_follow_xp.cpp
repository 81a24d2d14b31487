// One x_p source (issue 26): the calibration capture plan's x_p (studio wizard's geometric
// plan default, `fovea-cli calibrate --hoe-shift optimal`) and the virtual bench's follow-gaze
// table take x_p from model/analysis/hoe_travel.h, so at a gaze the sweep samples they give
// the sweep's x_p (to 0.01 mm) under either x_p rule.
#include <QtTest>
#include "app/embedded_scene.h"
#include "tests/sweep_at_gaze.h"
#include "tests/test_paths.h"

#include <cmath>

#include "devices/bench/follow_gaze_table.h"
#include "devices/calibration/capture_plan.h"
#include "model/analysis/analysis_registry.h"
#include "model/analysis/hoe_travel.h"
#include "model/scene/scene_io.h"

namespace tst_follow_xp {

using namespace fovea;
using namespace fovea::devices;

namespace {
using fovea::embeddedDefaultScene;
}  // namespace

class TestFollowXp : public QObject {
  Q_OBJECT
 private slots:
  void planAndBenchTableTakeTheSweepsXp() {
    Scene scene = embeddedDefaultScene();
    QCOMPARE(scene.eye.gaze_range_deg[1], 20.0);  // 9 table samples over [-20, 20]: 20 is one
    for (const XpRule rule : {XpRule::PlateauMiddle, XpRule::FollowFocus}) {
      scene.view.xp_rule = xpRuleName(rule);
      const nlohmann::json doc = fovea::testing::sweepAtYaw(scene, 20.0, rule);
      const double sweep_xp = doc["samples"][0]["hoe_shift_mm"].get<double>();
      const double plan = analysedHoeShift(scene)({20.0, 0.0})[0];
      const auto table = computeFollowGazeTable(scene);
      QVERIFY(table.ok());
      const double bench = table.value->hoeShift({20.0, 0.0})[0];
      const QString msg =
          QString("%1: sweep %2, plan %3, bench %4").arg(xpRuleName(rule)).arg(sweep_xp).arg(plan).arg(bench);
      QVERIFY2(std::abs(plan - sweep_xp) < 0.01 && std::abs(bench - sweep_xp) < 0.01, qPrintable(msg));
      QVERIFY(table.value->source.find(xpRuleName(rule)) != std::string::npos);
      QCOMPARE(table.value->hoeShift({0.0, 0.0})[0], 0.0);  // a zero gaze component stays at the design
      QCOMPARE(analysedHoeShift(scene)({20.0, 0.0})[1], 0.0);
    }
  }
};

QTEST_APPLESS_MAIN(TestFollowXp)

}  // namespace tst_follow_xp
#include "tst_follow_xp.moc"

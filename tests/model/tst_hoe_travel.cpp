// One x_p and one FOV (issue 26): the least-squares focus against closed forms, the seed's
// follow-focus x_p rule, and the single x_p source (model/analysis/hoe_travel.h) against the
// sweep; the FOV a trace shows (model/analysis/trace_fov.h) against the sweep's evaluator.
#include <QtTest>

#include <cmath>

#include "app/embedded_scene.h"
#include "model/analysis/analysis_registry.h"
#include "model/analysis/hoe_focus.h"
#include "model/analysis/hoe_travel.h"
#include "model/analysis/trace_fov.h"
#include "model/scene/scene_geometry.h"
#include "model/scene/scene_io.h"
#include "tests/sweep_at_gaze.h"

namespace tst_hoe_travel {

using namespace fovea;

namespace {
using fovea::embeddedDefaultScene;
}  // namespace

class TestHoeTravel : public QObject {
  Q_OBJECT
 private slots:
  void raysThroughOnePointFocusThere() {
    // Every ray passes through Q: each term (I - d d^T)(Q - o) vanishes, so P = Q.
    const Eigen::Vector3d q(1.5, -2.0, 30.0);
    std::vector<Eigen::Vector3d> o, d;
    for (int i = 0; i < 7; ++i) {
      const Eigen::Vector3d origin(std::cos(i) * 10.0, std::sin(2.0 * i) * 8.0, -5.0 + i);
      o.push_back(origin);
      d.push_back((q - origin) * (0.5 + i));  // any length
    }
    const auto f = leastSquaresFocus(o, d);
    QVERIFY(f.has_value());
    QVERIFY2((f->point - q).norm() < 1e-9, qPrintable(QString::number((f->point - q).norm())));
    QVERIFY(f->rms_distance_mm < 1e-9);
  }

  void twoSkewLinesFocusMidwayOnTheirCommonPerpendicular() {
    // x axis at z = 0 and y axis at z = 2: the common perpendicular is the z axis, the point
    // minimising the sum of squared distances its midpoint (0, 0, 1), each 1 away.
    const auto f = leastSquaresFocus({{5, 0, 0}, {0, -3, 2}}, {{1, 0, 0}, {0, 2, 0}});
    QVERIFY(f.has_value());
    QVERIFY((f->point - Eigen::Vector3d(0, 0, 1)).norm() < 1e-12);
    QVERIFY(std::abs(f->rms_distance_mm - 1.0) < 1e-12);
  }

  void parallelRaysHaveNoFocus() {
    QVERIFY(!leastSquaresFocus({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 0, 1}, {0, 0, 2}, {0, 0, -1}}).has_value());
    QVERIFY(!leastSquaresFocus({{0, 0, 0}}, {{0, 0, 1}}).has_value());
  }

  void theHoeFocusMovesWithThePlate() {
    const Scene scene = embeddedDefaultScene();
    const auto f0 = hoeFocus(scene, {0.0, 0.0});
    const auto f1 = hoeFocus(scene, {1.0, 0.0});
    QVERIFY(f0 && f1);
    QVERIFY(f0->rays > 1000);
    // At zero gaze the recorded focus is the design's pupil centre (the eye is placed there).
    const EyePlacement eye = placeEye(scene, 0.0, 0.0);
    QVERIFY2((f0->focus.point - eye.pupil_center).norm() < 0.5,
             qPrintable(QString("%1 mm").arg((f0->focus.point - eye.pupil_center).norm())));
    // A 1 mm plate shift moves the focus ~1 mm along bench x (the fringes move with the plate).
    const double dx = f1->focus.point.x() - f0->focus.point.x();
    QVERIFY2(dx > 0.8 && dx < 1.2, qPrintable(QString::number(dx)));
  }

  void followFocusPutsTheFocusOnTheRotatedPupilCentre() {
    const Scene scene = embeddedDefaultScene();
    const FovEvaluator eval = hoeTravelEvaluator();
    GazeStudyOptions o = hoeTravelStudyOptions(XpRule::FollowFocus);
    const GazeSample s = optimiseShift(scene, eval, 20.0, GazeAxis::Yaw, ShiftMethod::Hoe, o);
    QVERIFY(std::abs(s.focus_lateral_miss_mm) <= o.focus_tolerance_mm);
    // Recompute the miss independently at the returned shift.
    const auto f = hoeFocus(scene, {s.shift_mm, 0.0}, o.focus);
    const EyePlacement eye = placeEye(scene, 20.0, 0.0);
    QVERIFY(f.has_value());
    QVERIFY(std::abs(f->focus.point.x() - eye.pupil_center.x()) <= o.focus_tolerance_mm);
    QVERIFY(std::abs((f->focus.point - eye.pupil_center).dot(eye.gaze) - s.focus_axial_miss_mm) < 1e-9);
    // The plateau middle differs (docs/seed-reproduction.md: +2.96 mm at +20 deg).
    const GazeSample m =
        optimiseShift(scene, eval, 20.0, GazeAxis::Yaw, ShiftMethod::Hoe, hoeTravelStudyOptions(XpRule::PlateauMiddle));
    QVERIFY(std::isnan(m.focus_axial_miss_mm));
    QVERIFY2(s.shift_mm > m.shift_mm + 0.2, qPrintable(QString("%1 vs %2").arg(s.shift_mm).arg(m.shift_mm)));
  }

  void hoeTravelIsTheSweepsXp() {
    // sweep (the registry's run function, as fovea-cli sweep) at +20 deg against hoeTravel,
    // the x_p of the live trace and the report (tests/devices/tst_follow_xp.cpp: the capture
    // plan and the bench's table; tests/gui/tst_one_fov.cpp: the studio's live trace).
    Scene scene = embeddedDefaultScene();
    for (const XpRule rule : {XpRule::PlateauMiddle, XpRule::FollowFocus}) {
      scene.view.xp_rule = xpRuleName(rule);
      const nlohmann::json doc = fovea::testing::sweepAtYaw(scene, 20.0, rule);
      QCOMPARE(doc["xp_rule"].get<std::string>(), std::string(xpRuleName(rule)));
      const double sweep_xp = doc["samples"][0]["hoe_shift_mm"].get<double>();
      const HoeTravel travel = hoeTravel(scene, {20.0, 0.0}, sceneXpRule(scene));
      const QString msg =
          QString("%1: sweep %2, hoeTravel %3").arg(xpRuleName(rule)).arg(sweep_xp).arg(travel.shift_mm[0]);
      QVERIFY2(std::abs(travel.shift_mm[0] - sweep_xp) < 0.01, qPrintable(msg));
      QCOMPARE(travel.shift_mm[1], 0.0);  // zero pitch: the design position
      if (rule == XpRule::PlateauMiddle) {
        QVERIFY2(std::abs(sweep_xp - 2.96) < 0.005, qPrintable(msg));  // docs/seed-reproduction.md
        QVERIFY(doc["samples"][0]["focus_axial_miss_mm"].is_null());
      } else {
        QVERIFY(doc["samples"][0]["focus_axial_miss_mm"].is_number());
      }
    }
  }

  void aTraceShowsTheSweepsFov() {
    // trace_fov.h's exact FOV is the sweep evaluator's FOV for the same gaze and shift.
    const Scene scene = embeddedDefaultScene();
    TraceOptions o;
    o.gaze_deg = std::array<double, 2>{20.0, 0.0};
    o.hoe_shift_mm = {2.964, 0.0};
    const FovDeg exact = exactTraceFov(scene, o);
    const FovSample s = hoeTravelEvaluator()(scene, gazeQuery(20.0, GazeAxis::Yaw, ShiftMethod::Hoe, 2.964));
    QCOMPARE(exact.horizontal, s.horizontal_deg);
    QCOMPARE(exact.vertical, s.vertical_deg);
    QVERIFY2(std::abs(exact.horizontal - 89.23) < 0.01, qPrintable(QString::number(exact.horizontal)));  // issue 26
    // Zero gaze, unmoved: 90.00 x 78.58 (docs/seed-reproduction.md, issue 26).
    TraceOptions z;
    z.gaze_deg = std::array<double, 2>{0.0, 0.0};
    const FovDeg f0 = exactTraceFov(scene, z);
    QVERIFY2(std::abs(f0.horizontal - 90.00) < 0.005 && std::abs(f0.vertical - 78.58) < 0.005,
             qPrintable(QString("%1 x %2").arg(f0.horizontal).arg(f0.vertical)));
  }
};

QTEST_APPLESS_MAIN(TestHoeTravel)

}  // namespace tst_hoe_travel
#include "tst_hoe_travel.moc"

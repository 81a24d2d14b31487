// Gaze studies (A.3/A.4) and parameter sweeps on a closed-form FOV model whose optimum
// shifts and eye-box borders are known exactly, so the search algorithms are checked
// against numbers (the traced prototype is checked in tst_gaze_studies_traced).
#include <QtTest>

#include <atomic>
#include <cmath>
#include <numbers>

#include "app/embedded_scene.h"
#include "model/analysis/eyebox_walk.h"
#include "model/analysis/gaze_studies.h"
#include "model/scene/scene_geometry.h"
#include "model/scene/scene_io.h"

namespace tst_gaze_studies {

using namespace fovea;

namespace {
using fovea::embeddedDefaultScene;

// Maxwellian toy: the focus sits at the HOE shift (or moves -0.5 mm per mm of source
// shift); rays miss the pupil when the focus is more than 1 mm from the pupil centre
// (15 deg of FOV lost per mm), and Bragg mismatch darkens the HOE edge beyond 4.5 mm of
// HOE shift (20 deg per mm) or 2 mm of source shift.
FovSample toy(const Scene& scene, const FovQuery& q) {
  const double pupil = placeEye(scene, q.gaze_deg[0], q.gaze_deg[1]).pupil_center.x();
  const double s = q.hoe_shift_mm[0], zs = q.source_shift_mm;
  const double focus = s - 0.5 * zs;
  const double miss = std::max(0.0, std::abs(pupil - focus) - 1.0);
  FovSample f;
  f.horizontal_deg =
      90.0 - 15.0 * miss - 20.0 * std::max(0.0, std::abs(s) - 4.5) - 20.0 * std::max(0.0, std::abs(zs) - 2.0);
  f.vertical_deg = 78.0;
  f.diagonal_deg = std::hypot(f.horizontal_deg, f.vertical_deg);
  f.mean_efficiency = 0.9 * std::exp(-(s / 6) * (s / 6) - (zs / 4) * (zs / 4) - (pupil - focus) * (pupil - focus) / 4);
  f.efficiency_uniformity = 0.8;
  return f;
}
// Brute-force reference of the same definitions on the toy: x_p the middle of the shifts
// whose FOV is within 5 deg of the bracket's best (edges by dense scan), eye box the pupil range around zero
// whose FOV at x_p stays within 3 deg of the zero-gaze one (dense scan of the gaze).
double referenceFov(const Scene& scene, double gaze, ShiftMethod m) {
  auto fov = [&](double s) {
    FovQuery q;
    q.gaze_deg = {gaze, 0};
    if (m == ShiftMethod::Hoe) q.hoe_shift_mm = {s, 0};
    if (m == ShiftMethod::Source) q.source_shift_mm = s;
    return toy(scene, q).horizontal_deg;
  };
  const double guess = m == ShiftMethod::Hoe ? placeEye(scene, gaze, 0).pupil_center.x() : 0.0;
  const double half = m == ShiftMethod::Hoe ? 4.0 : 10.0;
  double best = -1e9;  // F*: the best of the 17-point bracket, as documented
  for (int i = 0; i < 17; ++i) best = std::max(best, fov(guess - half + 2 * half * i / 16));
  double lo = 1e9, hi = -1e9;
  for (double s = guess - half; s <= guess + half; s += 0.002)
    if (fov(s) >= best - 5.0) lo = std::min(lo, s), hi = std::max(hi, s);
  return fov(0.5 * (lo + hi));
}

std::pair<double, double> referenceEyeBox(const Scene& scene, ShiftMethod m) {
  const double reference = referenceFov(scene, 0, m);
  double g_hi = 0, g_lo = 0;
  while (referenceFov(scene, g_hi + 0.1, m) >= reference - 3.0) g_hi += 0.1;
  while (referenceFov(scene, g_lo - 0.1, m) >= reference - 3.0) g_lo -= 0.1;
  return {placeEye(scene, g_lo, 0).pupil_center.x(), placeEye(scene, g_hi, 0).pupil_center.x()};
}
}  // namespace

class TestGazeStudies : public QObject {
  Q_OBJECT
 private slots:
  void shiftFollowsThePupilAndGrowsMonotonically() {
    const Scene scene = embeddedDefaultScene();
    const auto r = sweepGaze(scene, toy, -20, 20, 5, GazeAxis::Yaw, ShiftMethod::Hoe);
    QVERIFY(r.ok());
    QCOMPARE(r.value->samples.size(), std::size_t{9});
    for (std::size_t i = 1; i < r.value->samples.size(); ++i)
      QVERIFY(r.value->samples[i].shift_mm > r.value->samples[i - 1].shift_mm);
    for (const auto& s : r.value->samples) {
      // The plateau FOV >= 90 - 5: |P - s| <= 1 + 5/15 (pupil), |s| <= 4.5 + 5/20 (Bragg);
      // x_p is its middle (P: pupil displacement 11.5 sin(gaze)).
      const double p = 11.5 * std::sin(s.gaze_deg * std::numbers::pi / 180);
      const double lo = std::max(p - 4.0 / 3.0, -4.75), hi = std::min(p + 4.0 / 3.0, 4.75);
      QVERIFY2(std::abs(s.shift_mm - 0.5 * (lo + hi)) < 0.03,
               qPrintable(QString("%1 vs %2").arg(s.shift_mm).arg(0.5 * (lo + hi))));
      QVERIFY(std::abs(s.plateau_mm[0] - lo) < 0.03 && std::abs(s.plateau_mm[1] - hi) < 0.03);
      QVERIFY(s.fov.horizontal_deg > 87.0);  // inside the eye box: (nearly) full FOV
    }
  }

  void eyeBoxBordersMatchABruteForceReference() {
    const Scene scene = embeddedDefaultScene();
    const auto r = sweepGaze(scene, toy, -40, 40, 5, GazeAxis::Yaw, ShiftMethod::Hoe);
    QVERIFY(r.ok());
    const EyeBox& eb = r.value->eyebox;
    QVERIFY(eb.lower_bounded && eb.upper_bounded);
    const auto [p_lo, p_hi] = referenceEyeBox(scene, ShiftMethod::Hoe);
    QVERIFY2(std::abs(eb.pupil_range_mm[1] - p_hi) < 0.08,
             qPrintable(QString("%1 vs %2").arg(eb.pupil_range_mm[1]).arg(p_hi)));
    QVERIFY(std::abs(eb.pupil_range_mm[0] - p_lo) < 0.08);
    QVERIFY(std::abs(eb.width_mm - (p_hi - p_lo)) < 0.15);
    QCOMPARE(eb.reference_fov_deg, 90.0);
    // Outside the eye box the FOV drops below the tolerance.
    for (const auto& s : r.value->samples)
      if (s.gaze_deg > eb.gaze_range_deg[1] + 1e-9 || s.gaze_deg < eb.gaze_range_deg[0] - 1e-9)
        QVERIFY(s.fov.horizontal_deg < 87.0);
  }

  // The fit's lazy eye box (eyebox_walk.h) is the full sweep's, to the bit, with fewer x_p
  // searches: only the gazes up to the first failure on each side and the bisections.
  void lazyEyeBoxWalkEqualsTheFullSweep() {
    const Scene scene = embeddedDefaultScene();
    for (const auto& [method, step] :
         {std::pair{ShiftMethod::Hoe, 5.0}, std::pair{ShiftMethod::Source, 2.5}, std::pair{ShiftMethod::None, 5.0}}) {
      const auto full = sweepGaze(scene, toy, -40, 40, step, GazeAxis::Yaw, method);
      QVERIFY(full.ok());
      std::atomic<int> searches{0};
      const EyeBox lazy = walkEyeBox(sweepGazes(-40, 40, step), GazeAxis::Yaw, {}, [&](double g) {
        ++searches;
        return optimiseShift(scene, toy, g, GazeAxis::Yaw, method);
      });
      const EyeBox& eb = full.value->eyebox;
      QCOMPARE(lazy.width_mm, eb.width_mm);
      QCOMPARE(lazy.gaze_range_deg, eb.gaze_range_deg);
      QCOMPARE(lazy.pupil_range_mm, eb.pupil_range_mm);
      QCOMPARE(lazy.travel_mm, eb.travel_mm);
      QCOMPARE(lazy.reference_fov_deg, eb.reference_fov_deg);
      QCOMPARE(lazy.lower_bounded, eb.lower_bounded);
      QCOMPARE(lazy.upper_bounded, eb.upper_bounded);
      // The full sweep: every gaze, the reference and 6 bisections per border.
      const int full_searches = static_cast<int>(sweepGazes(-40, 40, step).size()) + 1 + 2 * 6;
      QVERIFY2(searches < full_searches, qPrintable(QString("%1 of %2").arg(int(searches)).arg(full_searches)));
    }
  }

  void sourceShiftEyeBoxIsSmaller() {
    const Scene scene = embeddedDefaultScene();
    const auto hoe = sweepGaze(scene, toy, -40, 40, 5, GazeAxis::Yaw, ShiftMethod::Hoe);
    const auto src = sweepGaze(scene, toy, -40, 40, 2.5, GazeAxis::Yaw, ShiftMethod::Source);
    const auto none = sweepGaze(scene, toy, -40, 40, 5, GazeAxis::Yaw, ShiftMethod::None);
    QVERIFY(hoe.ok() && src.ok() && none.ok());
    const auto [p_lo, p_hi] = referenceEyeBox(scene, ShiftMethod::Source);
    QVERIFY2(std::abs(src.value->eyebox.width_mm - (p_hi - p_lo)) < 0.15,
             qPrintable(QString("%1 vs %2").arg(src.value->eyebox.width_mm).arg(p_hi - p_lo)));
    // Static: the focus stays at 0, 1 mm of pupil slack + 3/15 mm of tolerance each side.
    QVERIFY(std::abs(none.value->eyebox.width_mm - 2 * (1 + 3.0 / 15)) < 0.1);
    for (const auto& s : none.value->samples) QCOMPARE(s.shift_mm, 0.0);
    QVERIFY(hoe.value->eyebox.width_mm > 2.5 * src.value->eyebox.width_mm);
  }

  void pitchAxisUsesTheVerticalFov() {
    const Scene scene = embeddedDefaultScene();
    const auto r = sweepGaze(scene, toy, -10, 10, 10, GazeAxis::Pitch, ShiftMethod::Hoe);
    QVERIFY(r.ok());
    // The toy's vertical FOV is flat: every pitch is inside, no border found.
    QVERIFY(!r.value->eyebox.upper_bounded && !r.value->eyebox.lower_bounded);
    QCOMPARE(r.value->eyebox.gaze_range_deg[1], 10.0);
  }

  void parameterPathsEditTheSerializedScene() {
    const Scene scene = embeddedDefaultScene();
    QCOMPARE(withParameter(scene, "eye.relief_mm", 25).eye.relief_mm, 25.0);
    QCOMPARE(withParameter(scene, "hoe_layers[1].shrinkage_percent", -1.5).hoe_layers[1].shrinkage_percent, -1.5);
    QCOMPARE(withParameter(scene, "hoe.rotation_deg[0]", 2).hoe.pose.rotation_deg[0], 2.0);
    QCOMPARE(withParameter(scene, "hoe_layers[0].recording.wavelength_nm", 650).hoe_layers[0].recording.wavelength_nm,
             650.0);
    QCOMPARE(parameterValue(scene, "eye.pupil_diameter_mm"), 5.0);
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, withParameter(scene, "eye.nonexistent", 1));
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, withParameter(scene, "hoe_layers[7].n1", 1));
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, withParameter(scene, "name", 1));
    try {
      withParameter(scene, "eye.pupil_diameter_mm", -2);
      QFAIL("validation did not apply");
    } catch (const std::invalid_argument& e) {
      QVERIFY(std::string(e.what()).find("eye.pupil_diameter_mm") != std::string::npos);
    }
  }

  void sensitivityReportsEachValue() {
    const Scene scene = embeddedDefaultScene();
    // Eye decentration moves the pupil away from the fixed focus: FOV loses 15 deg/mm past 1 mm.
    const auto r = sensitivitySweep(scene, toy, "eye.lateral_offset_mm[0]", 0, 3, 4);
    QVERIFY(r.ok());
    QCOMPARE(r.value->size(), std::size_t{4});
    const double expected[] = {90, 90, 75, 60};
    for (int i = 0; i < 4; ++i) {
      QCOMPARE((*r.value)[i].value, double(i));
      QVERIFY(std::abs((*r.value)[i].fov.horizontal_deg - expected[i]) < 1e-9);
    }
  }

  void cancelledSweepReportsNothing() {
    std::atomic<bool> cancel{true};
    StudyControl c;
    c.cancel = &cancel;
    const auto r = sweepGaze(embeddedDefaultScene(), toy, -20, 20, 5, GazeAxis::Yaw, ShiftMethod::Hoe, {}, c);
    QCOMPARE(r.status, StudyStatus::Cancelled);
    QVERIFY(!r.value);
  }
};

QTEST_GUILESS_MAIN(TestGazeStudies)

}  // namespace tst_gaze_studies
#include "tst_gaze_studies.moc"

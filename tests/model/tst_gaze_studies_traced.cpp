// Seed-shaped checks of the gaze studies on the traced prototype bench (A.3, A.4): the HOE
// shift grows monotonically with gaze, the FOV is held inside the eye box and drops
// outside it, and moving the HOE gives an eye box several times the source-shift one.
// Modest ray counts (one wavelength) keep it fast.
#include <QtTest>

#include "app/embedded_scene.h"
#include "model/analysis/gaze_studies.h"
#include "model/analysis/trace_evaluator.h"
#include "model/scene/scene_io.h"

using namespace fovea;

namespace {
Scene prototype() { return *parseScene(embeddedDefaultSceneJson(), "prototype").scene; }
FovEvaluator evaluator() {
  TraceEvaluatorOptions o;
  o.rays = 600;
  o.wavelength_nm = 532.0;
  return traceEvaluator(o);
}
}  // namespace

class TestGazeStudiesTraced : public QObject {
  Q_OBJECT
 private slots:
  void initTestCase() {
    if (!traceEvaluatorAvailable()) QSKIP("the HOE tracer is not in this build yet");
  }

  void hoeShiftGrowsWithGazeAndHoldsTheFov() {
    const Scene s = prototype();
    const auto r = sweepGaze(s, evaluator(), -20, 20, 10, GazeAxis::Yaw, ShiftMethod::Hoe);
    QVERIFY(r.ok());
    const auto& v = r.value->samples;
    for (std::size_t i = 1; i < v.size(); ++i)
      QVERIFY2(v[i].shift_mm > v[i - 1].shift_mm,
               qPrintable(QString("shift %1 at %2 deg, %3 at %4 deg")
                              .arg(v[i - 1].shift_mm)
                              .arg(v[i - 1].gaze_deg)
                              .arg(v[i].shift_mm)
                              .arg(v[i].gaze_deg)));
    // Zero gaze needs (almost) no shift; +-20 deg needs a few mm (seed: -3.44 .. +3.40).
    QVERIFY(std::abs(v[2].shift_mm) < 0.5);
    QVERIFY(v.back().shift_mm > 1.0 && v.back().shift_mm < 8.0);
    QVERIFY(v.front().shift_mm < -1.0 && v.front().shift_mm > -8.0);
  }

  void fovDropsOutsideTheEyeBoxAndHoeBeatsSource() {
    const Scene s = prototype();
    const auto eval = evaluator();
    const auto hoe = sweepGaze(s, eval, -45, 45, 7.5, GazeAxis::Yaw, ShiftMethod::Hoe);
    const auto src = sweepGaze(s, eval, -45, 45, 2.5, GazeAxis::Yaw, ShiftMethod::Source);
    QVERIFY(hoe.ok() && src.ok());
    const EyeBox& eb = hoe.value->eyebox;
    QVERIFY(eb.width_mm > 0);
    // Outside the eye box, the FOV is below the zero-gaze FOV by more than the tolerance.
    for (const auto& smp : hoe.value->samples)
      if (smp.gaze_deg > eb.gaze_range_deg[1] + 1e-9 || smp.gaze_deg < eb.gaze_range_deg[0] - 1e-9)
        QVERIFY(smp.fov.horizontal_deg < eb.reference_fov_deg - 1.0 + 1e-9);
    QVERIFY(eb.upper_bounded || eb.lower_bounded);
    QVERIFY2(eb.width_mm > 2.5 * src.value->eyebox.width_mm,
             qPrintable(QString("HOE %1 mm vs source %2 mm").arg(eb.width_mm).arg(src.value->eyebox.width_mm)));
  }
};

QTEST_GUILESS_MAIN(TestGazeStudiesTraced)
#include "tst_gaze_studies_traced.moc"

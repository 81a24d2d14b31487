// Seed-shaped checks of the gaze studies on the traced prototype bench (A.3, A.4): the HOE
// shift grows monotonically with gaze, the FOV is held inside the eye box and drops
// outside it, moving the HOE gives an eye box several times what moving the source adds,
// and the traced study is identical whatever the thread count. One wavelength and a
// modest ray count keep it fast (the CLI default is 12000 rays x 3 wavelengths).
#include <QtTest>

#include <atomic>
#include <cmath>

#include "app/embedded_scene.h"
#include "model/analysis/gaze_studies.h"
#include "model/analysis/trace_evaluator.h"
#include "model/scene/scene_io.h"

namespace tst_gaze_studies_traced {

using namespace fovea;

namespace {
using fovea::embeddedDefaultScene;
FovEvaluator evaluator() {
  TraceEvaluatorOptions o;
  o.rays = 3000;
  o.wavelength_nm = 532.0;
  return traceEvaluator(o);
}
}  // namespace

class TestGazeStudiesTraced : public QObject {
  Q_OBJECT
 private slots:
  void continuousFovSeesHoles() {
    // A full row of lit rays with one dark ray in the middle: the extent spans the row,
    // the continuous FOV only the wider half.
    std::vector<TracedRay> rays;
    for (int i = 0; i < 11; ++i) {
      TracedRay r;
      r.source = r.hoe_point = r.out_direction = Eigen::Vector3d::Zero();
      r.hits_hoe = true;
      r.exits = true;
      r.in_pupil = i != 4;
      r.efficiency = 0.5;
      r.wavelength_nm = 532;
      r.pixel = {i, 0};
      r.field_deg = {-50.0 + 10.0 * i, 1.0};
      rays.push_back(r);
    }
    const ContinuousFov c = continuousFov(rays, 0.1);
    QCOMPARE(c.horizontal_deg, 50.0);  // columns 5..10: -0 .. +50
    QCOMPARE(c.vertical_deg, 0.0);
    // A second row further from the field centre, fully lit and wider: not the line of sight.
    for (int i = 0; i < 13; ++i) {
      TracedRay r = rays.front();
      r.in_pupil = true;
      r.pixel = {i, 1};
      r.field_deg = {-60.0 + 10.0 * i, 20.0};
      rays.push_back(r);
    }
    QCOMPARE(continuousFov(rays, 0.1).horizontal_deg, 50.0);
    QCOMPARE(continuousFov(rays, 0.1).vertical_deg, 19.0);  // column 5: pitch 1 .. 20
  }

  void hoeShiftGrowsWithGazeAndHoldsTheFov() {
    const Scene s = embeddedDefaultScene();
    const auto r = sweepGaze(s, evaluator(), -20, 20, 10, GazeAxis::Yaw, ShiftMethod::Hoe);
    QVERIFY(r.ok());
    const auto& v = r.value->samples;
    for (std::size_t i = 1; i < v.size(); ++i)
      QVERIFY2(v[i].shift_mm > v[i - 1].shift_mm + 0.3, qPrintable(QString("shift %1 at %2 deg, %3 at %4 deg")
                                                                       .arg(v[i - 1].shift_mm)
                                                                       .arg(v[i - 1].gaze_deg)
                                                                       .arg(v[i].shift_mm)
                                                                       .arg(v[i].gaze_deg)));
    // Zero gaze needs (almost) no shift; +-20 deg needs a few mm (seed: -3.44 .. +3.40).
    QVERIFY2(std::abs(v[2].shift_mm) < 0.3, qPrintable(QString::number(v[2].shift_mm)));
    QVERIFY(v.back().shift_mm > 1.5 && v.back().shift_mm < 5.0);
    QVERIFY(v.front().shift_mm < -1.5 && v.front().shift_mm > -5.0);
    // Inside +-20 deg the FOV is held near the zero-gaze ~89 deg.
    for (const auto& smp : v) QVERIFY2(smp.fov.horizontal_deg > 80.0, qPrintable(QString::number(smp.gaze_deg)));
  }

  void fovDropsOutsideTheEyeBoxAndHoeBeatsSource() {
    const Scene s = embeddedDefaultScene();
    const auto eval = evaluator();
    const auto hoe = sweepGaze(s, eval, -45, 45, 7.5, GazeAxis::Yaw, ShiftMethod::Hoe);
    const auto src = sweepGaze(s, eval, -30, 30, 7.5, GazeAxis::Yaw, ShiftMethod::Source);
    const auto none = sweepGaze(s, eval, -30, 30, 7.5, GazeAxis::Yaw, ShiftMethod::None);
    QVERIFY(hoe.ok() && src.ok() && none.ok());
    const EyeBox& eb = hoe.value->eyebox;
    QVERIFY(eb.lower_bounded && eb.upper_bounded);
    QVERIFY2(eb.width_mm > 8.0 && eb.width_mm < 20.0, qPrintable(QString::number(eb.width_mm)));
    // Outside the eye box the FOV is below the zero-gaze FOV by more than the tolerance
    // (3 deg), and far outside it is well below.
    for (const auto& smp : hoe.value->samples) {
      if (smp.gaze_deg > eb.gaze_range_deg[1] + 1e-9 || smp.gaze_deg < eb.gaze_range_deg[0] - 1e-9)
        QVERIFY(smp.fov.horizontal_deg < eb.reference_fov_deg - 3.0);
      if (std::abs(smp.gaze_deg) >= 45) QVERIFY(smp.fov.horizontal_deg < eb.reference_fov_deg - 10.0);
    }
    const double w_hoe = eb.width_mm, w_src = src.value->eyebox.width_mm, w_static = none.value->eyebox.width_mm;
    const QString widths = QString("HOE %1, source %2, static %3 mm").arg(w_hoe).arg(w_src).arg(w_static);
    // The HOE shift's eye box is about twice the source shift's; what each adds to the
    // static eye box (the pupil's own slack) is several times larger for the HOE (seed: ~5x).
    QVERIFY2(w_hoe > 1.7 * w_src, qPrintable(widths));
    QVERIFY2(w_src > w_static, qPrintable(widths));
    QVERIFY2(w_hoe - w_static > 3.0 * (w_src - w_static), qPrintable(widths));
  }

  void walkedBracketGivesTheFullBracketsShift() {
    // x_p over the 41 gazes of the benchmark sweep (-20..20 deg by 1 deg) by the walked
    // bracket and by the full 17-point bracket (the reference). Both bisect each plateau edge
    // from a 0.5 mm grid interval edge_bisections times, so the optimiser's resolution is
    // 2 half / (n - 1) / 2^edge_bisections (7.8 µm): x_p may differ by at most that.
    const Scene s = embeddedDefaultScene();
    const FovEvaluator traced = evaluator();
    std::atomic<long long> traces{0};
    const FovEvaluator eval = [&](const Scene& sc, const FovQuery& q) {
      ++traces;
      return traced(sc, q);
    };
    GazeStudyOptions walked, full;
    full.full_bracket = true;
    const double resolution =
        2.0 * full.shift_half_range_mm / (full.bracket_points - 1) / std::pow(2.0, full.edge_bisections);
    double worst = 0;
    long long traces_walked = 0, traces_full = 0;
    for (int i = 0; i <= 40; ++i) {
      const double gaze = -20.0 + i;
      traces = 0;
      const GazeSample a = optimiseShift(s, eval, gaze, GazeAxis::Yaw, ShiftMethod::Hoe, walked);
      traces_walked += traces.exchange(0);
      const GazeSample b = optimiseShift(s, eval, gaze, GazeAxis::Yaw, ShiftMethod::Hoe, full);
      traces_full += traces.exchange(0);
      worst = std::max(worst, std::abs(a.shift_mm - b.shift_mm));
      QVERIFY2(std::abs(a.shift_mm - b.shift_mm) <= resolution,
               qPrintable(QString("gaze %1: x_p %2 walked, %3 full").arg(gaze).arg(a.shift_mm).arg(b.shift_mm)));
      QCOMPARE(a.best_fov_deg, b.best_fov_deg);
    }
    qInfo("41 gazes: max |x_p walked - full| %.3g mm (resolution %.3g mm); traces per gaze %.1f walked, %.1f full",
          worst, resolution, traces_walked / 41.0, traces_full / 41.0);
    QVERIFY(traces_walked < traces_full);
  }

  void identicalWithOneOrTwoThreads() {
    const Scene s = embeddedDefaultScene();
    auto run = [&](int threads) {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
      return sweepGaze(s, evaluator(), 0, 20, 10, GazeAxis::Yaw, ShiftMethod::Hoe);
    };
    const auto one = run(1), two = run(2);
    QVERIFY(one.ok() && two.ok());
    for (std::size_t i = 0; i < one.value->samples.size(); ++i) {
      QCOMPARE(one.value->samples[i].shift_mm, two.value->samples[i].shift_mm);
      QCOMPARE(one.value->samples[i].fov.horizontal_deg, two.value->samples[i].fov.horizontal_deg);
      QCOMPARE(one.value->samples[i].fov.mean_efficiency, two.value->samples[i].fov.mean_efficiency);
    }
    QCOMPARE(one.value->eyebox.width_mm, two.value->eyebox.width_mm);
  }
};

QTEST_GUILESS_MAIN(TestGazeStudiesTraced)

}  // namespace tst_gaze_studies_traced
#include "tst_gaze_studies_traced.moc"

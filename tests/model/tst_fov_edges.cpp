// The exact FOV estimator (model/analysis/fov_edges.h) and its single-ray tracer
// (model/physics/ray_probe.h): the probe returns the pipeline's values at the pipeline's own
// grid rays; the edge estimator meets the closed form of a plate-edge-limited field and the
// dense estimator converges to it as the ray count grows (within the dense one's ray spacing).
#include <QtTest>

#include <cmath>
#include <numbers>

#include "app/embedded_scene.h"
#include "model/analysis/fov_edges.h"
#include "model/analysis/gaze_studies.h"
#include "model/analysis/trace_evaluator.h"
#include "model/physics/projector_rays.h"
#include "model/physics/ray_probe.h"
#include "model/physics/trace_pipeline.h"
#include "model/scene/scene_io.h"
#include "model/units.h"

namespace tst_fov_edges {

using namespace fovea;

namespace {

using fovea::embeddedDefaultScene;

ContinuousFov denseFov(const Scene& scene, int rays, const std::array<double, 2>& gaze, double lambda) {
  TraceOptions t;
  t.gaze_deg = gaze;
  t.rays = rays;
  t.wavelength_nm = lambda;
  t.keep_field_rays = true;
  t.cull_to_pupil = true;
  TracePipeline p;
  return continuousFov(p.run(scene, t).field_rays, t.efficiency_threshold);
}

ContinuousFov edgesFov(const Scene& scene, const std::array<double, 2>& gaze, double lambda, double tol = 0.002) {
  RayProbeSetup s;
  s.gaze_deg = gaze;
  EdgeFovOptions o;
  o.tolerance_deg = tol;
  return edgeFov(RayProbe(scene, s), {lambda}, o).fov;
}
}  // namespace

class TestFovEdges : public QObject {
  Q_OBJECT
 private slots:
  void probeEqualsThePipelineAtItsGridRays() {
    Scene scene = embeddedDefaultScene();
    TraceOptions t;
    t.gaze_deg = std::array<double, 2>{12.0, -4.0};
    t.hoe_shift_mm = {1.5, -0.5};
    t.source_shift_mm = 2.0;
    t.rays = 900;
    t.keep_field_rays = true;
    TracePipeline pipeline;
    const TraceResult r = pipeline.run(scene, t);
    RayProbeSetup s;
    s.gaze_deg = *t.gaze_deg;
    s.hoe_shift_mm = t.hoe_shift_mm;
    s.source_shift_mm = t.source_shift_mm;
    const RayProbe probe(scene, s);
    const auto [nx, ny] = projectorGrid(scene.projector, t.rays);
    const auto [th, tv] = probe.halfTan();
    int in_pupil = 0;
    QVERIFY(r.field_rays.size() > 500);
    for (const FieldRay& f : r.field_rays) {
      const double x = th * ((2.0 * f.pixel[0] + 1.0) / nx - 1.0), y = tv * ((2.0 * f.pixel[1] + 1.0) / ny - 1.0);
      const ProbeRay p = probe.trace(x, y, f.wavelength_nm);
      QVERIFY(p.on_plate);
      QCOMPARE(p.in_pupil, f.in_pupil);
      QVERIFY2(std::abs(p.efficiency - f.efficiency) < 1e-9, qPrintable(QString::number(p.efficiency - f.efficiency)));
      if (!f.in_pupil) continue;
      ++in_pupil;
      QVERIFY(std::abs(p.field_deg[0] - f.field_deg[0]) < 1e-9 && std::abs(p.field_deg[1] - f.field_deg[1]) < 1e-9);
    }
    QVERIFY(in_pupil > 100);
    // A ray outside the plate does not reach it.
    QVERIFY(!probe.trace(th, tv, 532.0).on_plate || !probe.trace(-th, -tv, 532.0).on_plate);
  }

  void plateEdgeLimitedFieldMeetsTheClosedForm() {
    // Maxwellian recording (signal focus at the pupil centre, 22 mm in front of the plate) read
    // at its own wavelength: every diffracted ray passes the pupil centre, so at zero gaze the
    // field ends at the plate's edges (lit: efficiency 0.68-0.86 there): FOV = 2 atan(half size /
    // relief), 90 deg x 78.58 deg for the prototype's 44 x 36 mm plate.
    for (const std::array<double, 2> size : {std::array<double, 2>{44.0, 36.0}, std::array<double, 2>{24.0, 16.0}}) {
      Scene scene = embeddedDefaultScene();
      scene.hoe.size_mm = size;
      const ContinuousFov e = edgesFov(scene, {0.0, 0.0}, 532.0, 0.001);
      const double h = 2.0 * std::atan(0.5 * size[0] / 22.0) / kDeg, v = 2.0 * std::atan(0.5 * size[1] / 22.0) / kDeg;
      QVERIFY2(std::abs(e.horizontal_deg - h) < 0.005, qPrintable(QString("%1 vs %2").arg(e.horizontal_deg).arg(h)));
      QVERIFY2(std::abs(e.vertical_deg - v) < 0.005, qPrintable(QString("%1 vs %2").arg(e.vertical_deg).arg(v)));
      // The dense estimator falls short of it by up to about a ray spacing.
      const ContinuousFov d = denseFov(scene, 16000, {0.0, 0.0}, 532.0);
      QVERIFY(d.horizontal_deg <= h + 1e-9 && d.horizontal_deg > h - 3.0);
    }
  }

  void denseConvergesToTheEdges() {
    // Gazes with the HOE shifted after them (the Maxwellian focus inside the tilted pupil).
    const Scene scene = embeddedDefaultScene();
    struct Case {
      std::array<double, 2> gaze, shift;
    };
    for (const Case c : {Case{{15.0, 0.0}, {2.0, 0.0}}, Case{{-10.0, 0.0}, {-1.0, 0.0}}}) {
      RayProbeSetup s;
      s.gaze_deg = c.gaze;
      s.hoe_shift_mm = c.shift;
      EdgeFovOptions o;
      o.tolerance_deg = 0.002;
      const ContinuousFov e = edgeFov(RayProbe(scene, s), {532.0}, o).fov;
      QVERIFY(e.horizontal_deg > 85 && e.vertical_deg > 70);
      double last = 0;
      for (const int rays : {4000, 16000, 64000}) {
        TraceOptions t;
        t.gaze_deg = c.gaze;
        t.hoe_shift_mm = c.shift;
        t.rays = rays;
        t.wavelength_nm = 532.0;
        t.keep_field_rays = true;
        t.cull_to_pupil = true;
        TracePipeline p;
        const ContinuousFov d = continuousFov(p.run(scene, t).field_rays, 0.1);
        const auto [nx, ny] = projectorGrid(scene.projector, rays);
        // Two ray spacings (one per edge) in field angle: near the plate's edges the field moves up to ~6x the
        // projector angle.
        const double spacing = 6.0 * std::max(scene.projector.fov_deg[0] / nx, scene.projector.fov_deg[1] / ny);
        last = std::max(std::abs(d.horizontal_deg - e.horizontal_deg), std::abs(d.vertical_deg - e.vertical_deg));
        QVERIFY2(last <= 2.0 * spacing, qPrintable(QString("rays %1: dense %2/%3 edges %4/%5 spacing %6")
                                                       .arg(rays)
                                                       .arg(d.horizontal_deg)
                                                       .arg(d.vertical_deg)
                                                       .arg(e.horizontal_deg)
                                                       .arg(e.vertical_deg)
                                                       .arg(spacing)));
      }
      QVERIFY2(last < 1.0, qPrintable(QString::number(last)));
    }
  }

  void toleranceSetsTheError() {
    const Scene scene = embeddedDefaultScene();
    const ContinuousFov fine = edgesFov(scene, {0.0, 0.0}, 532.0, 1e-4);
    for (const double tol : {0.2, 0.05, 0.01}) {
      const ContinuousFov c = edgesFov(scene, {0.0, 0.0}, 532.0, tol);
      QVERIFY2(std::abs(c.horizontal_deg - fine.horizontal_deg) <= 2.0 * tol + 1e-6,
               qPrintable(QString("tol %1: %2 vs %3").arg(tol).arg(c.horizontal_deg).arg(fine.horizontal_deg)));
    }
  }

  void evaluatorUsesTheEdges() {
    const Scene scene = embeddedDefaultScene();
    TraceEvaluatorOptions o;
    o.fov_method = FovMethod::Edges;
    o.wavelength_nm = 532.0;
    o.edge_tolerance_deg = 0.002;
    FovQuery q;
    const FovSample f = traceEvaluator(o)(scene, q);
    const ContinuousFov e = edgesFov(scene, {0.0, 0.0}, 532.0);
    QCOMPARE(f.horizontal_deg, e.horizontal_deg);
    QVERIFY(f.mean_efficiency > 0.1 && f.mean_efficiency <= 1.0 && f.rays_in_pupil > 0);
    QVERIFY(f.extent_horizontal_deg >= f.horizontal_deg - 5.0 && f.extent_horizontal_deg <= f.horizontal_deg);
    // only_axis (the x_p search's hint): the read FOV to the bit, the other scan line skipped.
    for (const int axis : {0, 1}) {
      FovQuery one = q;
      one.gaze_deg = {10.0, 0.0};
      one.hoe_shift_mm = {2.0, 0.0};
      const FovSample all = traceEvaluator(o)(scene, {one.gaze_deg, one.hoe_shift_mm});
      one.only_axis = axis;
      const FovSample only = traceEvaluator(o)(scene, one);
      QCOMPARE(axis == 0 ? only.horizontal_deg : only.vertical_deg, axis == 0 ? all.horizontal_deg : all.vertical_deg);
      QCOMPARE(axis == 0 ? only.vertical_deg : only.horizontal_deg, 0.0);
      QVERIFY(all.horizontal_deg > 60.0 && all.vertical_deg > 40.0);
    }
    QCOMPARE(parseFovMethod("edges").value(), FovMethod::Edges);
    QCOMPARE(parseFovMethod("dense").value(), FovMethod::Dense);
    QVERIFY(!parseFovMethod("exact"));
  }
};

QTEST_APPLESS_MAIN(TestFovEdges)

}  // namespace tst_fov_edges
#include "tst_fov_edges.moc"

// The report's "bench at the chosen gazes" figures composed in the studio under Xvfb: each
// draws the report trace's ray fans with the live view's TraceOverlay (rays drawn, into the
// pupil, consistent with the trace), the retina view draws cells, and the live view — its
// overlay, plate shift, scene and camera — is exactly as before afterwards.
#include <QtTest>

#include <QUndoStack>

#include <cmath>

#include <vtkCamera.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>

#include "app/studio/live_trace_features.h"
#include "app/studio/main_window.h"
#include "app/studio/report_document.h"
#include "model/physics/projector_rays.h"
#include "model/physics/trace.h"
#include "viz/scene_view.h"
#include "viz/trace_overlay.h"
#include "widgets/gaze_panel.h"
#include "widgets/live_trace.h"
#include "widgets/scene_document.h"

namespace tst_report_figures {

using namespace fovea;

namespace {

studio::GazeTrace traceAt(const Scene& scene, std::array<double, 2> gaze, std::array<double, 2> shift, int rays) {
  studio::GazeTrace t;
  t.gaze_deg = gaze;
  t.hoe_shift_mm = shift;
  t.json = nlohmann::json::object();  // the trace analysis' numbers are not needed here
  TraceOptions o;
  o.gaze_deg = gaze;
  o.hoe_shift_mm = shift;
  o.rays = rays;
  o.keep_rays = true;
  t.rays = traceScene(scene, o);
  t.grid = projectorGrid(scene.projector, rays);
  return t;
}

std::array<double, 3> cameraPosition(viz::SceneView* v) {
  std::array<double, 3> p{};
  v->renderer()->GetActiveCamera()->GetPosition(p.data());
  return p;
}

}  // namespace

class TestReportFigures : public QObject {
  Q_OBJECT
 private slots:
  void gazeFiguresDrawTheReportTraceAndRestoreTheLiveView() {
    studio::MainWindow w;
    w.resize(1400, 900);
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    studio::LiveTraceFeatures* bench = w.liveTraceFeatures();
    // The live view: HOE follows a 6 deg gaze, so the plate is drawn shifted.
    bench->gazePanel()->setFollowGaze(true);
    bench->setStartGaze(6.0, 0.0);
    QVERIFY(bench->waitForTrace());
    viz::SceneView* view = w.sceneView();
    view->showStandardView(viz::StandardView::Isometric);
    view->renderToImage();
    const viz::TraceOverlayStats live = bench->overlay()->stats();
    const Eigen::Vector3d liveShift = view->hoeDisplayShift();
    const auto camera = cameraPosition(view);
    const std::size_t rayProps = view->layer("rays").size(), markProps = view->layer("eye_marks").size();
    QVERIFY(live.rays_drawn > 0 && liveShift.norm() > 0.0 && rayProps > 0);
    QVERIFY(bench->liveTrace()->latest()->hoe_shift_mm[0] != 0.0);

    // Report data: gaze 0 in place, gaze 6 with the plate at the live trace's x_p.
    studio::ReportData d;
    d.scene = w.document()->scene();
    d.scene.eye.gaze_deg = {0.0, 0.0};
    d.options.rays = 1000;
    d.options.gazes_deg = {{0.0, 0.0}, {6.0, 0.0}};
    const std::array<double, 2> xp = bench->liveTrace()->latest()->hoe_shift_mm;
    d.traces << traceAt(d.scene, {0.0, 0.0}, {0.0, 0.0}, d.options.rays)
             << traceAt(d.scene, {6.0, 0.0}, xp, d.options.rays);
    const studio::ReportContent c = studio::composeReport(w, d, {}, widgets::DisplayUnits{});

    QCOMPARE(c.gazeFigures.size(), 2);
    for (int i = 0; i < 2; ++i) {
      const studio::GazeFigureStats& s = c.gazeFigures[i];
      const TraceResult& t = d.traces[i].rays;
      QCOMPARE(s.figureId, QString("gaze-%1").arg(i + 1));
      QCOMPARE(s.hoe_shift_mm, d.traces[i].hoe_shift_mm);
      // Fans drawn from the trace: never more into the pupil than the trace found there.
      int hitPlate = 0, inPupil = 0;
      for (const TracedRay& r : t.ray_list) {
        hitPlate += r.hits_hoe;
        inPupil += r.hits_hoe && r.in_pupil;
      }
      QVERIFY2(s.overlay.rays_drawn > 0 && s.overlay.rays_drawn <= hitPlate, qPrintable(QString::number(hitPlate)));
      QVERIFY(s.overlay.rays_in_pupil > 0 && s.overlay.rays_in_pupil <= inPupil);
      QVERIFY(s.overlay.rays_in_pupil + s.overlay.rays_missing <= s.overlay.rays_drawn);
      QVERIFY2(s.overlay_pixels > 10 * s.overlay.rays_drawn, qPrintable(QString::number(s.overlay_pixels)));
      QVERIFY(s.retina_cells > 0);
    }
    // The figures: the gaze views, then per gaze the retina view and the retina map.
    QStringList ids;
    for (const auto& section : c.sections)
      for (const auto& f : section.figures) ids << f.id;
    QVERIFY2(ids.contains("gaze-1") && ids.contains("gaze-2") && ids.contains("retina-view-1") &&
                 ids.contains("retina-view-2") && ids.contains("retina-1"),
             qPrintable(ids.join(",")));

    // The live view as before: its overlay (same fans, same plate shift), scene and camera.
    const viz::TraceOverlayStats after = bench->overlay()->stats();
    QCOMPARE(after.rays_drawn, live.rays_drawn);
    QCOMPARE(after.rays_in_pupil, live.rays_in_pupil);
    QCOMPARE(after.rays_missing, live.rays_missing);
    QCOMPARE(view->hoeDisplayShift(), liveShift);
    QCOMPARE(view->layer("rays").size(), rayProps);
    QCOMPARE(view->layer("eye_marks").size(), markProps);
    QVERIFY(bench->overlay()->colorBar()->GetVisibility());
    QVERIFY(view->scene() == w.document()->scene());
    QCOMPARE(cameraPosition(view), camera);
    QCOMPARE(w.document()->undoStack()->count(), 0);  // composing edits nothing
  }

  // Printed figures: a light background, and the selection (highlight box, drag handles)
  // leaves no trace in them; the studio's look comes back afterwards.
  void figuresArePrintedWithoutHandlesOnALightBackground() {
    studio::MainWindow w;
    w.resize(1400, 900);
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    QVERIFY(w.liveTraceFeatures()->waitForTrace());
    viz::SceneView* view = w.sceneView();
    studio::ReportData d;
    d.scene = w.document()->scene();
    d.options.rays = 500;
    auto figure = [&](const char* id) {
      const studio::ReportContent c = studio::composeReport(w, d, {}, widgets::DisplayUnits{});
      for (const auto& section : c.sections)
        for (const auto& f : section.figures)
          if (f.id == id) return f.image;
      return QImage();
    };
    const QImage plain = figure("view-iso");
    QVERIFY(!plain.isNull());
    // Light: the corners are the background, near white.
    for (const QPoint p : {QPoint(2, 2), QPoint(plain.width() - 3, 2), QPoint(2, plain.height() - 3)})
      QVERIFY2(qGray(plain.pixel(p)) > 200, qPrintable(QString::number(qGray(plain.pixel(p)))));
    w.selectElement("hoe");
    QVERIFY(view->layer("handles").size() > 0 && view->layer("handles").isVisible());
    const QImage selected = figure("view-iso");
    QCOMPARE(selected, plain);
    // The studio's look again: dark background, handles shown.
    QVERIFY(!view->printLook());
    QVERIFY(view->layer("handles").isVisible());
    const QImage live = view->renderToImage();
    QVERIFY(qGray(live.pixel(2, 2)) < 100);
  }
};

QTEST_MAIN(TestReportFigures)

}  // namespace tst_report_figures
#include "tst_report_figures.moc"

// The live trace in the studio under Xvfb: gaze sliders change the model's gaze (one undo
// step per drag), "HOE follows gaze" applies x_p, a handle drag is one undo step in sync
// with the property editor, requests are coalesced and stale results dropped, and the
// overlay draws what the trace found (solid rays into the pupil, dashed ones missing it).
#include <QtTest>

#include <QLabel>

#include <algorithm>

#include <QCheckBox>
#include <QDir>
#include <QFile>
#include <QLineEdit>
#include <QSlider>
#include <QUndoStack>

#include <cmath>
#include <filesystem>

#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkProp.h>
#include <vtkScalarBarActor.h>

#include "app/studio/live_trace_features.h"
#include "app/studio/main_window.h"
#include "model/physics/projector_rays.h"
#include "model/physics/trace.h"
#include "model/scene/scene_geometry.h"
#include "viz/element_handles.h"
#include "viz/kspace_view.h"
#include "viz/scene_view.h"
#include "viz/trace_overlay.h"
#include "viz/vtk_gl_widget.h"
#include "widgets/display_panel.h"
#include "widgets/gaze_panel.h"
#include "widgets/handle_controller.h"
#include "widgets/live_trace.h"
#include "widgets/preferences.h"
#include "widgets/property_editor.h"
#include "widgets/retina_view.h"
#include "widgets/scene_document.h"

namespace tst_trace_views {

using namespace fovea;

class TestTraceViews : public QObject {
  Q_OBJECT
 private:
  std::unique_ptr<studio::MainWindow> w;
  studio::LiveTraceFeatures* bench() { return w->liveTraceFeatures(); }

 private slots:
  void init() {
    w = std::make_unique<studio::MainWindow>();
    w->resize(1600, 1000);
    w->show();
    QVERIFY(QTest::qWaitForWindowExposed(w.get()));
    w->sceneView()->renderToImage();
    QVERIFY(bench()->waitForTrace());
  }
  void cleanup() {
    w->document()->undoStack()->setClean();
    w.reset();
  }

  void firstTraceMatchesTheModel() {
    const auto r = bench()->liveTrace()->latest();
    QVERIFY(r);
    QVERIFY(r->error.empty());
    // The same numbers as a direct trace of the scene (4000 rays per wavelength).
    TraceOptions o;
    o.rays = 4000;
    const TraceResult direct = traceScene(w->document()->scene(), o);
    QCOMPARE(r->trace.fov_deg.horizontal, direct.fov_deg.horizontal);
    QCOMPARE(r->trace.rays_in_pupil, direct.rays_in_pupil);
    QVERIFY(r->trace.fov_deg.horizontal > 85.0);  // docs/physics.md: 88.0 deg at 4000 rays
    QCOMPARE(static_cast<int>(r->trace.ray_list.size()), 3 * r->grid[0] * r->grid[1]);
    // The horizontal fan: 25 rays per wavelength, all on the plate, all entering the pupil
    // at zero gaze (recorded in place: every ray converges to the pupil centre).
    const viz::TraceOverlayStats& s = bench()->overlay()->stats();
    QCOMPARE(s.rays_drawn, 3 * 25);
    QCOMPARE(s.rays_in_pupil, 3 * 25);
    QCOMPARE(s.rays_missing, 0);
    QVERIFY(!w->sceneView()->layer("rays").propsOf({}).empty());
    QVERIFY(bench()->overlay()->colorBar()->GetVisibility());
    // Retina view: the FOV box equals the trace's horizontal and vertical FOV.
    const auto& box = bench()->retinaView()->fovBox();
    QVERIFY(box.valid);
    QCOMPARE(box.yaw_max - box.yaw_min, r->trace.fov_deg.horizontal);
    QCOMPARE(box.pitch_max - box.pitch_min, r->trace.fov_deg.vertical);
    bench()->retinaView()->render(QSize(640, 480));  // counted while painting (the dock may be a hidden tab)
    QVERIFY(bench()->retinaView()->cellsDrawn() > 1000);
    // Grating-vector cloud: Bragg matched at zero gaze, the probe's K equals the recorded one.
    QVERIFY(bench()->kspaceView()->probePoints() > 1000);
    QVERIFY2(bench()->kspaceView()->maxDephasing() < 1e-6,
             qPrintable(QString::number(bench()->kspaceView()->maxDephasing())));
  }

  void dragShowsCoarseTracesAndEndsRefined() {
    widgets::GazePanel* gaze = bench()->gazePanel();
    gaze->setFollowGaze(true);
    QVERIFY(bench()->waitForTrace());
    QSlider* yaw = gaze->yawSlider();
    std::vector<std::shared_ptr<const widgets::LiveTraceResult>> seen;
    connect(bench()->liveTrace(), &widgets::LiveTrace::resultReady, this,
            [&](const std::shared_ptr<const widgets::LiveTraceResult>& r) { seen.push_back(r); });
    // A drag: pressed, 1 deg steps up to 15 deg with the event loop running between moves.
    // Each move's coarse trace is there when the move returns (same frame as the turned eye).
    yaw->setSliderDown(true);
    int moves = 0;
    for (int v = 2; v <= 30; v += 2) {
      yaw->setValue(v);
      ++moves;
      QCOMPARE(bench()->liveTrace()->latest()->generation, bench()->liveTrace()->newestGeneration());
      QCOMPARE(bench()->liveTrace()->latest()->trace.gaze_deg[0], v / 2.0);
      QTest::qWait(15);
    }
    QTest::qWait(40);
    // While the hand moved, one coarse trace was drawn per move (the view never froze).
    const auto coarse = std::count_if(seen.begin(), seen.end(),
                                      [](const auto& r) { return r->detail == widgets::TraceDetail::Coarse; });
    QCOMPARE(static_cast<int>(coarse), moves);
    QVERIFY(w->sceneView()->dragRendering());  // frames for speed until the refined one
    // ... drawn at the preference's resolution (default half) and magnified into the view.
    viz::SceneView* view = w->sceneView();
    view->renderToImage();
    const int fullWidth = view->renderWindow()->GetSize()[0], fullHeight = view->renderWindow()->GetSize()[1];
    QCOMPARE(view->lastRenderSize(), QSize(int(std::lround(fullWidth * 0.5)), int(std::lround(fullHeight * 0.5))));
    for (const auto& r : seen) {
      if (r->detail != widgets::TraceDetail::Coarse) continue;
      QCOMPARE(r->grid, projectorGrid(r->scene.projector, r->settings.coarse_rays));
      QVERIFY(r->shift_source != "search");  // x_p from the table or the last applied one
      QVERIFY(r->cloud.empty());
    }
    QCOMPARE(bench()->liveTrace()->latest()->detail, widgets::TraceDetail::Coarse);
    yaw->setSliderDown(false);
    // The hand rests: the refined trace of the final gaze replaces the coarse one.
    QVERIFY(bench()->waitForTrace());
    const auto r = bench()->liveTrace()->latest();
    QCOMPARE(r->detail, widgets::TraceDetail::Refined);
    QVERIFY(!w->sceneView()->dragRendering());  // depth-peeled again
    view->renderToImage();
    QCOMPARE(view->lastRenderSize(), QSize(fullWidth, fullHeight));  // and at full resolution
    QCOMPARE(r->trace.gaze_deg[0], 15.0);
    QCOMPARE(r->grid, projectorGrid(r->scene.projector, r->settings.rays));
    QCOMPARE(r->shift_source, std::string("search"));
    QVERIFY2(r->hoe_shift_mm[0] > 1.0 && r->hoe_shift_mm[0] < 5.0, qPrintable(QString::number(r->hoe_shift_mm[0])));
    QVERIFY(!r->cloud.empty());
    QVERIFY(bench()->overlay()->stats().rays_drawn > 0);
    QVERIFY(!gaze->findChild<QLabel*>("gazeReadout")->text().contains("refining"));
    QCOMPARE(w->document()->undoStack()->count(), 2);  // follow on, one drag
  }

  void dragResolutionFollowsThePreference() {
    // Edit > Preferences > "3-D view resolution while dragging" sets the drag frames' scale.
    widgets::PreferenceValues v = widgets::Preferences::instance().values();
    QCOMPARE(w->sceneView()->dragRenderScale(), v.dragResolutionPercent / 100.0);
    v.dragResolutionPercent = 75;
    widgets::Preferences::instance().setValues(v);
    QCOMPARE(w->sceneView()->dragRenderScale(), 0.75);
    w->sceneView()->setDragRendering(true);
    w->sceneView()->renderToImage();
    const int fullWidth = w->sceneView()->renderWindow()->GetSize()[0];
    QCOMPARE(w->sceneView()->lastRenderSize().width(), int(std::lround(fullWidth * 0.75)));
    w->sceneView()->setDragRendering(false);
    v.dragResolutionPercent = 50;
    widgets::Preferences::instance().setValues(v);
    QCOMPARE(w->sceneView()->dragRenderScale(), 0.5);
  }

  void sliderMoveChangesTheGaze() {
    widgets::GazePanel* gaze = bench()->gazePanel();
    QSlider* yaw = gaze->yawSlider();
    QUndoStack* stack = w->document()->undoStack();
    QSignalSpy sceneSpy(w->document(), &widgets::SceneDocument::sceneChanged);
    QSignalSpy results(bench()->liveTrace(), &widgets::LiveTrace::resultReady);
    // A drag of the slider: pressed, several values, released.
    const quint64 started = bench()->liveTrace()->jobsStarted();
    yaw->setSliderDown(true);
    for (int v = 1; v <= 28; ++v) yaw->setValue(v);  // 0.5 deg steps up to 14 deg
    yaw->setSliderDown(false);
    QCOMPARE(w->document()->scene().eye.gaze_deg[0], 14.0);
    QCOMPARE(w->document()->scene().eye.gaze_deg[1], 0.0);
    QCOMPARE(sceneSpy.count(), 28);
    QCOMPARE(stack->count(), 1);  // one drag, one undo step
    QCOMPARE(stack->undoText(), QString("Set gaze to 14.0°, 0.0°"));
    QVERIFY(w->isWindowModified());
    // The trace follows: one coarse trace per move (each delivered at once), then one
    // refined trace when the hand rests.
    QCOMPARE(results.count(), 28);
    QVERIFY(bench()->waitForTrace());
    QCOMPARE(results.count(), 29);
    QCOMPARE(bench()->liveTrace()->jobsStarted() - started, quint64{29});
    const auto r = bench()->liveTrace()->latest();
    QCOMPARE(r->detail, widgets::TraceDetail::Refined);
    QCOMPARE(r->trace.gaze_deg[0], 14.0);
    QVERIFY(r->reused_diffraction);  // only the gaze stage ran
    // At 14 deg without HOE travel the pupil has left the Maxwellian focus (physics.md:
    // nothing beyond ~12.5 deg), so the fan's rays miss it: dashed.
    QVERIFY(r->trace.fov_deg.horizontal < 10.0);
    QVERIFY(bench()->overlay()->stats().rays_missing > 0);
    // The keyboard moves by one step: a separate undo step.
    yaw->setFocus();
    QTest::keyClick(yaw, Qt::Key_Left);
    QCOMPARE(w->document()->scene().eye.gaze_deg[0], 13.5);
    QCOMPARE(stack->count(), 2);
    stack->undo();
    stack->undo();
    QCOMPARE(w->document()->scene().eye.gaze_deg[0], 0.0);
    QCOMPARE(yaw->value(), 0);
    QVERIFY(!w->isWindowModified());
  }

  void hoeFollowsGaze() {
    bench()->gazePanel()->setGaze(20.0, 0.0);
    QVERIFY(bench()->waitForTrace());
    const double fovFixed = bench()->liveTrace()->latest()->trace.fov_deg.horizontal;
    QCOMPARE(bench()->liveTrace()->latest()->hoe_shift_mm[0], 0.0);
    bench()->gazePanel()->setFollowGaze(true);
    QVERIFY(bench()->waitForTrace());
    const auto r = bench()->liveTrace()->latest();
    // physics.md / seed A.4: about +3.4 mm of travel restores ~86 deg at +20 deg gaze.
    QVERIFY2(r->hoe_shift_mm[0] > 1.0 && r->hoe_shift_mm[0] < 5.0, qPrintable(QString::number(r->hoe_shift_mm[0])));
    QCOMPARE(r->hoe_shift_mm[1], 0.0);
    QVERIFY2(r->trace.fov_deg.horizontal > 80.0 && fovFixed < 10.0,
             qPrintable(QString("%1 vs %2").arg(r->trace.fov_deg.horizontal).arg(fovFixed)));
    // The plate is drawn at its travelled place.
    const Eigen::Vector3d drawn = w->sceneView()->hoeDisplayShift();
    QCOMPARE(drawn.x(), r->hoe_shift_mm[0]);
    const double* b = w->sceneView()->sceneLayer().propsOf("hoe_layers[1]").front()->GetBounds();
    QVERIFY(std::abs(b[0] - (-22.0 + r->hoe_shift_mm[0])) < 1e-9);
  }

  void followGazeIsSavedWithTheSceneAndReopened() {
    // The case: a design saved at 15.5 deg gaze with "HOE follows gaze" on reopened
    // with FOV 0.0 x 0.0 because the flag was not saved. Now it is part of the scene file.
    bench()->gazePanel()->setGaze(15.5, 0.0);
    bench()->gazePanel()->setFollowGaze(true);
    QVERIFY(bench()->waitForTrace());
    const auto before = bench()->liveTrace()->latest();
    QVERIFY2(before->trace.fov_deg.horizontal > 60.0, qPrintable(QString::number(before->trace.fov_deg.horizontal)));
    const QString path =
        QDir(QDir::tempPath()).filePath("fovea-follow-gaze-%1.json").arg(QCoreApplication::applicationPid());
    QVERIFY(w->saveTo(path, false));
    w->document()->undoStack()->setClean();
    w.reset();

    w = std::make_unique<studio::MainWindow>();
    w->resize(1600, 1000);
    w->show();
    QVERIFY(QTest::qWaitForWindowExposed(w.get()));
    QVERIFY(w->openFile(path, false));
    QVERIFY(bench()->waitForTrace());
    QFile::remove(path);
    QVERIFY(bench()->gazePanel()->followGaze());
    QVERIFY(bench()->gazePanel()->findChild<QCheckBox*>("followGaze")->isChecked());  // the box shows it
    const auto after = bench()->liveTrace()->latest();
    QCOMPARE(after->trace.gaze_deg[0], 15.5);
    // The same travel and FOV as when it was saved (the x_p search is deterministic).
    QCOMPARE(after->hoe_shift_mm[0], before->hoe_shift_mm[0]);
    QCOMPARE(after->trace.fov_deg.horizontal, before->trace.fov_deg.horizontal);
    qInfo("reopened at 15.5 deg: following, x_p %.3f mm, FOV %.1f x %.1f deg", after->hoe_shift_mm[0],
          after->trace.fov_deg.horizontal, after->trace.fov_deg.vertical);
    // Without the flag the same gaze gives a far smaller FOV: the reopened numbers are not
    // the fixed-plate ones.
    bench()->gazePanel()->setFollowGaze(false);
    QVERIFY(bench()->waitForTrace());
    QVERIFY2(bench()->liveTrace()->latest()->trace.fov_deg.horizontal < before->trace.fov_deg.horizontal - 20.0,
             qPrintable(QString::number(bench()->liveTrace()->latest()->trace.fov_deg.horizontal)));
  }

  void dragIsOneUndoStep() {
    viz::SceneView* view = w->sceneView();
    w->selectElement("projector");
    viz::ElementHandles* handles = bench()->handles()->handles();
    QCOMPARE(handles->element(), QString("projector"));
    view->showStandardView(viz::StandardView::Top);
    view->renderToImage();
    const Eigen::Vector3d start = toVec(w->document()->scene().projector.pose.position_mm);
    const auto grip = view->widgetPositionOf(start + Eigen::Vector3d(viz::ElementHandles::kLength_mm - 3.0, 0, 0));
    const auto target = view->widgetPositionOf(start + Eigen::Vector3d(viz::ElementHandles::kLength_mm + 9.2, 0, 0));
    QVERIFY(grip && target);
    QCOMPARE(handles->axisAt(*grip), std::optional<int>(0));
    QUndoStack* stack = w->document()->undoStack();
    QSignalSpy finished(bench()->handles(), &widgets::HandleController::dragFinished);
    QTest::mousePress(view, Qt::LeftButton, {}, grip->toPoint());
    QVERIFY(bench()->handles()->isDragging());
    for (int i = 1; i <= 8; ++i) {
      const QPointF p = *grip + (*target - *grip) * (i / 8.0);
      QMouseEvent move(QEvent::MouseMove, p, view->mapToGlobal(p), Qt::NoButton, Qt::LeftButton, Qt::NoModifier);
      QApplication::sendEvent(view, &move);
    }
    // The property editor follows during the drag.
    auto* field = qobject_cast<QLineEdit*>(w->propertyEditor()->fieldFor("projector.position_mm[0]"));
    QVERIFY(field);
    QTest::mouseRelease(view, Qt::LeftButton, {}, target->toPoint());
    QVERIFY(!bench()->handles()->isDragging());
    const double moved = w->document()->scene().projector.pose.position_mm[0] - start.x();
    // Snapped to whole millimetres, about 12 mm along x; y and z untouched; camera unmoved.
    QVERIFY2(std::abs(moved - 12.0) <= 1.0, qPrintable(QString::number(moved)));
    QCOMPARE(moved, std::round(moved));
    QCOMPARE(w->document()->scene().projector.pose.position_mm[1], start.y());
    QCOMPARE(w->document()->scene().projector.pose.position_mm[2], start.z());
    QCOMPARE(field->text(), QString::number(start.x() + moved));
    QCOMPARE(stack->count(), 1);
    QVERIFY(stack->undoText().startsWith("Move projector along x by "));
    QCOMPARE(finished.count(), 1);
    QCOMPARE(w->selectedElement(), QString("projector"));  // the drag did not pick or deselect
    stack->undo();
    QCOMPARE(w->document()->scene().projector.pose.position_mm[0], start.x());
    QCOMPARE(field->text(), QString::number(start.x()));
    // Numeric entry: one exact move, one more step.
    QVERIFY(bench()->handles()->moveBy(2, -2.5));
    QCOMPARE(w->document()->scene().projector.pose.position_mm[2], start.z() - 2.5);
    QCOMPARE(stack->count(), 1);
  }

  // Drags ring `ring` from angle `from` by `by` degrees (eight mouse moves along the arc).
  void dragRing(int ring, double from, double by, Qt::KeyboardModifiers mods) {
    viz::SceneView* view = w->sceneView();
    viz::ElementHandles* handles = bench()->handles()->handles();
    auto send = [&](QEvent::Type type, double angle, Qt::MouseButton button, Qt::MouseButtons buttons) {
      const auto p = view->widgetPositionOf(handles->ringPoint(ring, angle));
      QVERIFY(p);
      QMouseEvent e(type, *p, view->mapToGlobal(*p), button, buttons, mods);
      QApplication::sendEvent(view, &e);
    };
    send(QEvent::MouseButtonPress, from, Qt::LeftButton, Qt::LeftButton);
    QVERIFY(bench()->handles()->isRotating());
    for (int i = 1; i <= 8; ++i) send(QEvent::MouseMove, from + by * i / 8.0, Qt::NoButton, Qt::LeftButton);
    send(QEvent::MouseButtonRelease, from + by, Qt::LeftButton, Qt::NoButton);
    QVERIFY(!bench()->handles()->isDragging());
  }

  void ringDragIsOneUndoStep() {
    viz::SceneView* view = w->sceneView();
    w->selectElement("projector");
    viz::ElementHandles* handles = bench()->handles()->handles();
    QCOMPARE(handles->ringCount(), 3);
    view->showStandardView(viz::StandardView::Top);  // the yaw ring (about +y) seen face-on
    view->renderToImage();
    // A grip on the yaw ring away from the arrows.
    std::optional<double> from;
    for (double a = 20.0; a < 360.0 && !from; a += 25.0) {
      const auto p = view->widgetPositionOf(handles->ringPoint(0, a));
      if (p && handles->ringAt(*p) == std::optional<int>(0) && !handles->axisAt(*p)) from = a;
    }
    QVERIFY(from);
    const auto start = w->document()->scene().projector.pose.rotation_deg;
    QUndoStack* stack = w->document()->undoStack();
    QSignalSpy finished(bench()->handles(), &widgets::HandleController::rotateFinished);
    auto* field = qobject_cast<QLineEdit*>(w->propertyEditor()->fieldFor("projector.rotation_deg[0]"));
    QVERIFY(field);

    // 7.3 deg about +y snaps to 7 deg of yaw; pitch and roll stay.
    dragRing(0, *from, 7.3, Qt::NoModifier);
    auto now = w->document()->scene().projector.pose.rotation_deg;
    QCOMPARE(now[0] - start[0], 7.0);
    QCOMPARE(now[1], start[1]);
    QCOMPARE(now[2], start[2]);
    QCOMPARE(stack->count(), 1);
    QVERIFY2(stack->undoText().startsWith("Rotate projector: yaw by 7"), qPrintable(stack->undoText()));
    QCOMPARE(finished.count(), 1);
    QCOMPARE(finished.front().at(2).toDouble(), 7.0);
    QCOMPARE(field->text().toDouble(), now[0]);  // the property editor follows
    QCOMPARE(w->selectedElement(), QString("projector"));
    stack->undo();
    QCOMPARE(w->document()->scene().projector.pose.rotation_deg, start);
    QCOMPARE(field->text().toDouble(), start[0]);

    // Shift: fine 0.1 deg steps, backwards across the ring.
    dragRing(0, *from, -2.34, Qt::ShiftModifier);
    const double fine = w->document()->scene().projector.pose.rotation_deg[0] - start[0];
    QVERIFY2(std::abs(fine + 2.34) <= 0.051 && std::abs(fine * 10 - std::round(fine * 10)) < 1e-9,
             qPrintable(QString::number(fine, 'g', 10)));
    QCOMPARE(stack->count(), 1);  // one step per drag (it replaced the undone one)

    // Numeric entry: roll by exactly 15 deg, one more step; the eye turns its gaze.
    QVERIFY(bench()->handles()->rotateBy(2, 15.0));
    QCOMPARE(w->document()->scene().projector.pose.rotation_deg[2], start[2] + 15.0);
    QCOMPARE(stack->count(), 2);
    w->selectElement("eye");
    QCOMPARE(bench()->handles()->handles()->ringCount(), 2);
    QVERIFY(bench()->handles()->rotateBy(0, 5.0));
    QCOMPARE(w->document()->scene().eye.gaze_deg[0], 5.0);
    QVERIFY(!bench()->handles()->rotateBy(2, 5.0));  // the eye has no roll ring
  }

  void ringAxesTurnTheirOwnAngle() {
    // Turning a pose by a small angle about each ring's axis changes exactly that angle.
    Scene s = w->document()->scene();
    s.hoe.pose.rotation_deg = {20.0, -10.0, 5.0};
    w->document()->resetTo(s, {}, "rings");
    w->selectElement("hoe");
    viz::ElementHandles* handles = bench()->handles()->handles();
    const Eigen::Matrix3d r0 = rotationFromDeg(s.hoe.pose.rotation_deg);
    for (int k = 0; k < 3; ++k) {
      std::array<double, 3> turned = s.hoe.pose.rotation_deg;
      turned[static_cast<std::size_t>(k)] += 3.0;
      const Eigen::Matrix3d expected = Eigen::AngleAxisd(3.0 * M_PI / 180.0, handles->ringAxis(k)) * r0;
      QVERIFY2((rotationFromDeg(turned) - expected).norm() < 1e-12, qPrintable(QString::number(k)));
    }
  }

  void eyeDragMovesReliefAndLateralOffset() {
    w->selectElement("eye");
    QCOMPARE(bench()->handles()->handles()->element(), QString("eye"));
    QVERIFY(bench()->handles()->moveBy(2, -3.0));  // away from the HOE
    QCOMPARE(w->document()->scene().eye.relief_mm, 25.0);
    QVERIFY(bench()->handles()->moveBy(0, 1.5));
    QCOMPARE(w->document()->scene().eye.lateral_offset_mm[0], 1.5);
    // A move the scene rules refuse (relief <= 0) changes nothing.
    QVERIFY(!bench()->handles()->moveBy(2, 40.0));
    QCOMPARE(w->document()->scene().eye.relief_mm, 25.0);
  }

  void requestsAreCoalescedAndStaleResultsDropped() {
    widgets::LiveTrace* t = bench()->liveTrace();
    QVERIFY(t->waitForIdle());
    const quint64 started = t->jobsStarted(), delivered = t->resultsDelivered(), dropped = t->resultsDropped();
    Scene s = w->document()->scene();
    widgets::LiveTraceSettings settings;
    // Ten requests in one event-loop turn: one job, one result, for the last scene.
    for (int i = 1; i <= 10; ++i) {
      s.eye.gaze_deg = {0.5 * i, 0.0};
      t->request(s, settings);
    }
    QVERIFY(t->waitForIdle());
    QCOMPARE(t->jobsStarted(), started + 1);
    QCOMPARE(t->resultsDelivered(), delivered + 1);
    QCOMPARE(t->latest()->scene.eye.gaze_deg[0], 5.0);
    // A request while a job runs: that job's result is stale and dropped.
    s.hoe_layers[0].n1 = 0.02;  // new diffraction: a real job
    t->request(s, settings);
    QTRY_COMPARE(t->jobsStarted(), started + 2);
    s.eye.gaze_deg = {-3.0, 1.0};
    t->request(s, settings);
    QVERIFY(t->waitForIdle());
    QCOMPARE(t->jobsStarted(), started + 3);
    QCOMPARE(t->resultsDropped(), dropped + 1);
    QCOMPARE(t->latest()->scene.eye.gaze_deg[1], 1.0);
    QCOMPARE(t->latest()->trace.gaze_deg[1], 1.0);
  }

  void wavelengthTogglesAndEfficiencyMap() {
    widgets::DisplayPanel* d = bench()->displayPanel();
    QCheckBox* green = d->wavelengthToggle(532.0);
    QVERIFY(green);
    green->setChecked(false);
    QCOMPARE(bench()->overlay()->stats().rays_drawn, 2 * 25);
    d->setShowEfficiencyMap(true);
    // One cell per grid cell whose four corner rays land on the plate.
    const auto r = bench()->liveTrace()->latest();
    const int nx = r->grid[0], ny = r->grid[1];
    int cells = 0;
    for (int y = 0; y + 1 < ny; ++y)
      for (int x = 0; x + 1 < nx; ++x)
        if (r->trace.ray_list[y * nx + x].hits_hoe && r->trace.ray_list[y * nx + x + 1].hits_hoe &&
            r->trace.ray_list[(y + 1) * nx + x].hits_hoe && r->trace.ray_list[(y + 1) * nx + x + 1].hits_hoe)
          ++cells;
    QVERIFY(cells > 300);
    QCOMPARE(bench()->overlay()->stats().effmap_cells, cells);
    QVERIFY(!w->sceneView()->layer("effmap").propsOf("hoe").empty());
    d->setShowRays(false);
    QCOMPARE(bench()->overlay()->stats().rays_drawn, 0);
    QVERIFY(w->sceneView()->layer("rays").size() == 0);
    green->setChecked(true);
    d->setShowRays(true);
    QCOMPARE(bench()->overlay()->stats().rays_drawn, 3 * 25);
  }
};

int main(int argc, char** argv) {
  viz::installDefaultSurfaceFormat();
  QApplication app(argc, argv);
  QApplication::setOrganizationName("FoveatedARStudioTest");
  QApplication::setApplicationName("tst_trace_views");
  TestTraceViews test;
  return QTest::qExec(&test, argc, argv);
}

}  // namespace tst_trace_views
#include "tst_trace_views.moc"

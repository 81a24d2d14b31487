#include "app/studio/live_trace_features.h"

#include <QDockWidget>
#include <QSlider>
#include <QStatusBar>
#include <QStyle>
#include <QStyleOptionSlider>
#include <QTimer>

#include <cstdio>

#include "app/studio/latency_probe.h"
#include "app/studio/main_window.h"
#include "model/scene/eye_scene.h"
#include "viz/kspace_view.h"
#include "viz/scene_view.h"
#include "viz/trace_overlay.h"
#include "widgets/binocular_top_view.h"
#include "widgets/display_panel.h"
#include "widgets/gaze_panel.h"
#include "widgets/handle_controller.h"
#include "widgets/live_trace.h"
#include "widgets/preferences.h"
#include "widgets/preview_panel.h"
#include "widgets/retina_panel.h"
#include "widgets/retina_view.h"
#include "widgets/scene_document.h"

namespace fovea::studio {

LiveTraceFeatures::LiveTraceFeatures(MainWindow* window) : QObject(window), window_(window) {
  widgets::SceneDocument* doc = window->document();
  trace_ = new widgets::LiveTrace(this);
  leftTrace_ = new widgets::LiveTrace(this);
  probe_ = LatencyProbe::createIfRequested(this);
  overlay_ = std::make_unique<viz::TraceOverlay>(window->sceneView());
  leftOverlay_ = std::make_unique<viz::TraceOverlay>(window->sceneView(), viz::OverlayRole::LeftEye);
  gaze_ = new widgets::GazePanel(doc, window);
  display_ = new widgets::DisplayPanel(window);
  retinaPanel_ = new widgets::RetinaPanel(window);
  retina_ = retinaPanel_->view();
  kspace_ = new viz::KSpaceView(window);
  kspace_->setObjectName("KSpaceView");
  handles_ = new widgets::HandleController(doc, window->sceneView(), this);

  QDockWidget* gazeDock = window->addPanel(gaze_, tr("Gaze"), "GazeDock", Qt::LeftDockWidgetArea);
  QDockWidget* raysDock = window->addPanel(display_, tr("Rays"), "RaysDock", Qt::LeftDockWidgetArea);
  window->tabifyDockWidget(gazeDock, raysDock);
  gazeDock->raise();
  retinaDock_ = window->addPanel(retinaPanel_, tr("Retina"), "RetinaDock", Qt::RightDockWidgetArea);
  kspaceDock_ = window->addPanel(kspace_, tr("Grating vectors"), "KSpaceDock", Qt::RightDockWidgetArea);
  window->tabifyDockWidget(retinaDock_, kspaceDock_);
  // The binocular top view: beside the Properties (dock_layout.cpp), so it shows with the Gaze
  // and Retina docks (a fourth tab beside the Retina dock's elides their titles at 1366x768).
  window->addPanel(gaze_->topView(), tr("Top view"), "TopViewDock", Qt::RightDockWidgetArea);
  retinaDock_->raise();

  connect(doc, &widgets::SceneDocument::sceneChanged, this, [this, doc] {
    display_->setWavelengths(doc->scene().projector.wavelengths_nm);
    retinaPanel_->setBinocular(doc->scene().binocular.has_value());
    requestTrace();
  });
  // The left eye's retina: its own trace, run while it is shown.
  connect(retinaPanel_, &widgets::RetinaPanel::eyeChanged, this, [this] {
    requestTrace();
    redraw();
  });
  connect(leftTrace_, &widgets::LiveTrace::resultReady, this, [this] { redraw(); });
  connect(display_, &widgets::DisplayPanel::traceRaysChanged, this, &LiveTraceFeatures::requestTrace);
  connect(display_, &widgets::DisplayPanel::overlayOptionsChanged, this, &LiveTraceFeatures::redraw);
  connect(gaze_, &widgets::GazePanel::followGazeChanged, this, &LiveTraceFeatures::requestTrace);
  connect(trace_, &widgets::LiveTrace::resultReady, this, &LiveTraceFeatures::showResult);
  connect(trace_, &widgets::LiveTrace::busyChanged, this,
          [this](bool busy) { gaze_->showResult(trace_->latest(), busy); });
  connect(window->sceneView(), &viz::SceneView::selectionChanged, handles_, &widgets::HandleController::setElement);
  connect(handles_, &widgets::HandleController::dragFinished, this, [this](const QString& el, int axis, double d) {
    window_->statusBar()->showMessage(
        tr("Moved %1 along %2 by %3 mm").arg(el, QString("xyz").mid(axis, 1)).arg(d, 0, 'g', 6), 4000);
  });
  connect(handles_, &widgets::HandleController::rotateFinished, this, [this](const QString& el, int ring, double d) {
    window_->statusBar()->showMessage(
        tr("Turned %1: %2 by %3 deg").arg(el, QStringList{"yaw", "pitch", "roll"}.value(ring)).arg(d, 0, 'g', 6), 4000);
  });
  // The 3-D view's resolution while dragging follows the preference.
  auto dragResolution = [this] {
    window_->sceneView()->setDragRenderScale(widgets::Preferences::instance().values().dragResolutionPercent / 100.0);
  };
  dragResolution();
  connect(&widgets::Preferences::instance(), &widgets::Preferences::changed, this, dragResolution);
  display_->setWavelengths(doc->scene().projector.wavelengths_nm);
  retinaPanel_->setBinocular(doc->scene().binocular.has_value());
  requestTrace();
  if (probe_)  // where a scripted drag grabs the yaw slider (scripts/measure-drag-latency.sh)
    QTimer::singleShot(6000, this, [this] {
      QSlider* s = gaze_->yawSlider();
      QStyleOptionSlider opt;
      opt.initFrom(s);
      opt.orientation = s->orientation();
      opt.minimum = s->minimum();
      opt.maximum = s->maximum();
      opt.sliderPosition = s->sliderPosition();
      opt.sliderValue = s->value();
      const QRect handle = s->style()->subControlRect(QStyle::CC_Slider, &opt, QStyle::SC_SliderHandle, s);
      const QPoint c = s->mapToGlobal(handle.center()), end = s->mapToGlobal(QPoint(s->width() - 4, 0));
      std::fprintf(stderr, "yaw-slider: %d %d %d\n", c.x(), c.y(), end.x());
    });
}

LiveTraceFeatures::~LiveTraceFeatures() = default;

void LiveTraceFeatures::requestTrace() {
  widgets::LiveTraceSettings s;
  s.rays = display_->traceRays();
  s.follow_gaze = gaze_->followGaze();
  // While the hand moves a slider or a handle: coarse traces, refined when it rests.
  const bool dragging = gaze_->isDragging() || handles_->isDragging();
  // Frames for speed from the first move; the refined result (showResult) restores them.
  if (dragging) window_->sceneView()->setDragRendering(true);
  const Scene& scene = window_->document()->scene();
  const widgets::TraceDetail detail = dragging ? widgets::TraceDetail::Coarse : widgets::TraceDetail::Refined;
  trace_->request(scene, s, detail);
  // A binocular scene's left eye: traced on every move too (its fans, pupil and HOE travel in
  // the 3-D view, its retina; both eyes per move, the budget x 2).
  if (scene.binocular) leftTrace_->request(eyeScene(scene, EyeSide::Left), s, detail);
  if (probe_ && dragging) probe_->noteRequest(trace_->newestGeneration());
}

void LiveTraceFeatures::showResult(const std::shared_ptr<const widgets::LiveTraceResult>& r) {
  if (probe_ && r) probe_->noteDelivered(r->generation);
  if (r && r->detail == widgets::TraceDetail::Refined) {
    window_->sceneView()->setDragRendering(false);
    // Once the first rays are on screen: compile what the first drag's frames will need.
    if (!dragRenderingPrepared_)
      QTimer::singleShot(0, this, [this] {
        if (dragRenderingPrepared_ || !window_->sceneView()->isVisible()) return;
        dragRenderingPrepared_ = true;
        window_->sceneView()->prepareDragRendering();
      });
  }
  gaze_->showResult(r, trace_->isBusy());
  redraw();
  if (probe_ && r) {
    const quint64 gen = r->generation;
    const char* detail = r->detail == widgets::TraceDetail::Coarse ? "coarse" : "refined";
    connect(
        window_->sceneView(), &QOpenGLWidget::frameSwapped, probe_,
        [this, gen, detail, ms = r->compute_ms] {
          probe_->noteDrawn(gen, detail, ms, window_->sceneView()->lastPaintMs());
        },
        Qt::SingleShotConnection);
  }
}

void LiveTraceFeatures::redraw() {
  const auto r = trace_->latest();
  const viz::TraceOverlayOptions o = display_->overlayOptions();
  if (!r || !r->error.empty()) {
    overlay_->clear();
  } else {
    overlay_->show(r->scene, r->trace, r->grid, r->hoe_shift_mm, o);
  }
  // The left eye's fans, pupil and fovea, its HOE at its own x_p (a binocular scene only).
  const auto l = leftTrace_->latest();
  if (r && r->error.empty() && l && l->error.empty() && window_->document()->scene().binocular)
    leftOverlay_->show(l->scene, l->trace, l->grid, l->hoe_shift_mm, o);
  else
    leftOverlay_->clear();
  retina_->setResult(retinaPanel_->eye() == EyeSide::Left ? leftTrace_->latest() : r, o.hidden_wavelengths_nm);
  // Coarse (dragging) traces carry no grating-vector cloud: the last refined one stays.
  if (r && r->detail == widgets::TraceDetail::Refined) kspace_->setCloud(r->cloud, o.hidden_wavelengths_nm);
}

bool LiveTraceFeatures::applyShowList(const QStringList& names, QString* error) {
  bool rays = false, effmap = false;
  for (const QString& raw : names) {
    const QString n = raw.trimmed().toLower();
    if (n == "rays") {
      rays = true;
    } else if (n == "effmap") {
      effmap = true;
    } else if (n == "kcloud") {
      kspaceDock_->show();
      kspaceDock_->raise();
    } else if (n == "retina") {
      retinaDock_->show();
      retinaDock_->raise();
    } else if (n == "retina-image") {  // the Foveated preview dock in its Retina image mode
      if (QDockWidget* d = window_->previewDock()) {
        d->show();
        d->raise();
      }
      if (widgets::PreviewPanel* p = window_->previewPanel()) p->setMode(widgets::PreviewPanel::Mode::RetinaImage);
    } else if (n == "bench") {
      if (QDockWidget* d = window_->devicesDock()) {
        d->show();
        d->raise();
      }
    } else if (n != "none" && !n.isEmpty()) {
      if (error)
        *error =
            tr("unknown view \"%1\" (expected rays, effmap, kcloud, retina, retina-image, bench or none)").arg(raw);
      return false;
    }
  }
  display_->setShowRays(rays);
  display_->setShowEfficiencyMap(effmap);
  return true;
}

void LiveTraceFeatures::setStartGaze(double yaw, double pitch) {
  widgets::SceneDocument* doc = window_->document();
  Scene s = doc->scene();
  s.eye.gaze_deg = {yaw, pitch};
  doc->resetTo(s, doc->filePath(), doc->displayName());
}

bool LiveTraceFeatures::waitForTrace(int timeout_ms) {
  return trace_->waitForIdle(timeout_ms) &&
         (!window_->document()->scene().binocular || leftTrace_->waitForIdle(timeout_ms));
}

}  // namespace fovea::studio

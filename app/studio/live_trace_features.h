#pragma once
// The live-trace part of the studio, composed on top of the main window: the LiveTrace
// controller (off-thread, coalesced), the 3D view's trace overlay (ray fans, efficiency map,
// pupil and fovea, colour bar), the grating-vector cloud view, the retina view, the gaze and
// ray-display docks, and the drag handles. MainWindow creates one; everything else is here.

#include <QObject>
#include <QStringList>

#include <memory>

class QDockWidget;

namespace fovea::viz {
class KSpaceView;
class TraceOverlay;
}  // namespace fovea::viz

namespace fovea::widgets {
class DisplayPanel;
class GazePanel;
class HandleController;
class LiveTrace;
class RetinaPanel;
class RetinaView;
struct LiveTraceResult;
}  // namespace fovea::widgets

namespace fovea::studio {

class MainWindow;
class LatencyProbe;

class LiveTraceFeatures : public QObject {
  Q_OBJECT
 public:
  explicit LiveTraceFeatures(MainWindow* window);
  ~LiveTraceFeatures() override;

  widgets::LiveTrace* liveTrace() const { return trace_; }
  widgets::GazePanel* gazePanel() const { return gaze_; }
  widgets::DisplayPanel* displayPanel() const { return display_; }
  widgets::RetinaView* retinaView() const { return retina_; }
  // The Retina dock: the view and, on a binocular scene, its eye selector.
  widgets::RetinaPanel* retinaPanel() const { return retinaPanel_; }
  // The left eye's trace (binocular scenes, while the Retina dock shows the left eye).
  widgets::LiveTrace* leftTrace() const { return leftTrace_; }
  viz::KSpaceView* kspaceView() const { return kspace_; }
  viz::TraceOverlay* overlay() const { return overlay_.get(); }
  viz::TraceOverlay* leftOverlay() const { return leftOverlay_.get(); }
  widgets::HandleController* handles() const { return handles_; }

  // --show: any of "rays", "effmap", "kcloud", "retina" (rays and effmap switch the 3D
  // layers, kcloud and retina raise their docks). Returns false on an unknown name.
  bool applyShowList(const QStringList& names, QString* error = nullptr);
  // Sets the scene's gaze without an undo step (command line, before any edit).
  void setStartGaze(double yaw_deg, double pitch_deg);
  // Waits (running the event loop) until the newest trace is drawn; false on timeout.
  bool waitForTrace(int timeout_ms = 120000);
  // Redraws the overlay, retina and k-cloud from the newest live result (e.g. after the
  // report borrowed the overlay for its gaze figures).
  void redraw();

 private:
  void requestTrace();
  void showResult(const std::shared_ptr<const widgets::LiveTraceResult>& result);

  MainWindow* window_;
  widgets::LiveTrace* trace_ = nullptr;
  widgets::GazePanel* gaze_ = nullptr;
  widgets::DisplayPanel* display_ = nullptr;
  widgets::RetinaView* retina_ = nullptr;
  widgets::RetinaPanel* retinaPanel_ = nullptr;
  widgets::LiveTrace* leftTrace_ = nullptr;
  viz::KSpaceView* kspace_ = nullptr;
  widgets::HandleController* handles_ = nullptr;
  std::unique_ptr<viz::TraceOverlay> overlay_;
  std::unique_ptr<viz::TraceOverlay> leftOverlay_;  // a binocular scene's left eye
  LatencyProbe* probe_ = nullptr;                   // FOVEA_LATENCY_LOG only
  bool dragRenderingPrepared_ = false;              // SceneView::prepareDragRendering() ran
  QDockWidget* retinaDock_ = nullptr;
  QDockWidget* kspaceDock_ = nullptr;
};

}  // namespace fovea::studio

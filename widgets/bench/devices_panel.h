#pragma once
// The studio's bench panel: the scene's motorised axes and the eye camera, live.
//
//  - Connect / Disconnect. The panel connects by itself when a scene is opened: to the USB
//    controllers of the scene's stage bindings when they are plugged in, else to the virtual
//    bench (APT emulators, virtual eye camera through the simulated optics), marked VIRTUAL
//    in an orange banner and on the camera image.
//  - Axes (axis_table.h): per axis the element position (the scene's coordinates), state,
//    jog, Home, Go to; the controller set-up read on connect in the axis name's tooltip.
//  - Keyboard (panel focused): Left / Right jog the selected axis, Up / Down select the axis,
//    + / - double / halve the step. Esc stops every axis at once (anywhere in the window).
//  - Refusals (soft limits: nothing is sent; limits in the row's frame and the user's units),
//    device errors (the controller's own code and text) and emergency stops appear in the
//    axis row's state ("refused", "stopped at X"), the status line and, through message(),
//    the Messages dock, all at once.
//  - One gaze: the scene's eye.gaze_deg (the Gaze dock sets it; setGaze() here sets it too).
//  - Eye camera (eye_camera_box.h): live view with crosshair, exposure and gain, and the
//    test pattern the virtual displays show.
//  - Follow gaze (follow_gaze_box.h): the HOE stages track x_p(alpha) from the gaze study,
//    the micro-OLED x_f(alpha) and the camera the gaze itself.
//  - Calibration capture wizard (capture_wizard.h), with the same x_p(alpha).
//
// Threads: the axis workers and the camera loop never touch widgets; their results come
// back as queued calls. The panel owns the LiveBench (devices/bench/live_bench.h).
#include <QPointer>
#include <QWidget>

#include <array>
#include <future>
#include <memory>
#include <optional>
#include <thread>
#include <vector>

#include "devices/bench/live_bench.h"
#include "widgets/bench/capture_wizard.h"

class QLabel;
class QPushButton;
class QTimer;

namespace fovea::widgets {

class SceneDocument;
class AxisTable;
class EyeCameraBox;
class FollowGazeBox;
class PupilTrackerView;

struct DevicesPanelOptions {
  bool auto_connect = true;               // connect when a scene is opened
  bool allow_hardware = true;             // look for USB controllers and V4L2 cameras
  std::shared_ptr<devices::Clock> clock;  // virtual bench clock (default: real time)
  bool live_camera = true;                // run the camera loop while the panel is visible
  bool analysed_follow = true;            // x_p(alpha) from the gaze study (else geometric only)
};

class DevicesPanel : public QWidget {
  Q_OBJECT
 public:
  explicit DevicesPanel(SceneDocument* document, QWidget* parent = nullptr, DevicesPanelOptions options = {});
  ~DevicesPanel() override;

  bool isConnected() const { return live_ != nullptr; }
  bool isVirtual() const { return live_ && live_->isVirtual(); }
  devices::LiveBench* liveBench() { return live_.get(); }
  QString statusText() const;
  QString bannerText() const;
  double stepSize() const;
  void setStepSize(double step);
  void setSpeed(double speed);
  void setSelectedAxis(const QString& key);  // "hoe.x"
  QString selectedAxis() const;
  CaptureWizard* wizard() const { return wizard_; }
  PupilTrackerView* pupilTracker() const { return tracker_; }
  // Element position of an axis from its last snapshot (nullopt: unknown / no such axis).
  std::optional<double> axisPosition(const QString& key) const;
  bool followGaze() const;
  bool hasCameraFrame() const;
  bool isStarting() const { return connect_thread_.joinable(); }
  // The gaze study's x_p(alpha) table (follow gaze) is complete.
  bool followTableReady() const;
  QString axisStateText(const QString& axis_key) const;  // the row's state column
  QString followInfoText() const;

 public slots:
  void connectBench();
  void disconnectBench();
  void emergencyStop();
  void homeAll();
  void jog(const QString& axis_key, int direction);  // +1 forward, -1 reverse
  void goTo(const QString& axis_key, double element_value);
  void setFollowGaze(bool on);
  void setGaze(double yaw_deg, double pitch_deg);
  void setTestPattern(int index);  // 0 off, 1 both checkerboards, 2 projector, 3 micro-OLED, 4 white
  void openCaptureWizard();

 signals:
  void benchConnected(bool is_virtual);
  void benchDisconnected();
  void statusChanged(const QString& text);
  void message(const QString& text, bool error);  // every report, for the Messages dock

 protected:
  void keyPressEvent(QKeyEvent* event) override;
  void showEvent(QShowEvent* event) override;
  void hideEvent(QHideEvent* event) override;

 private:
  void startBench(bool announce);
  void finishConnect(int generation, const std::shared_ptr<std::unique_ptr<devices::LiveBench>>& made,
                     const QString& error, const QString& camera_error);
  void refresh();
  void report(const QString& text, bool error);
  void onSceneChanged();
  Scene currentScene() const;

  SceneDocument* document_;
  DevicesPanelOptions options_;
  std::unique_ptr<devices::LiveBench> live_;
  std::vector<std::future<void>> connecting_;
  std::thread connect_thread_;  // builds the LiveBench off the GUI thread
  int connect_generation_ = 0;  // a start whose generation is stale is dropped
  bool want_connected_ = false;
  std::array<double, 2> scene_gaze_{0.0, 0.0};

  QLabel* banner_ = nullptr;
  QLabel* status_ = nullptr;
  QPushButton *connect_ = nullptr, *disconnect_ = nullptr, *homeAll_ = nullptr, *estop_ = nullptr;
  AxisTable* axes_ = nullptr;
  FollowGazeBox* follow_ = nullptr;
  EyeCameraBox* camera_ = nullptr;
  PupilTrackerView* tracker_ = nullptr;
  QPushButton* wizardButton_ = nullptr;
  QTimer* timer_ = nullptr;
  QPointer<CaptureWizard> wizard_;
};

}  // namespace fovea::widgets

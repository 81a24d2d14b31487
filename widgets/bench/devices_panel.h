#pragma once
// The studio's bench panel: the scene's motorised axes and the eye camera, live.
//
//  - Connect / Disconnect. The panel connects by itself when a scene is opened: to the USB
//    controllers of the scene's stage bindings when they are plugged in, else to the virtual
//    bench (APT emulators, virtual eye camera through the simulated optics), marked VIRTUAL
//    in an orange banner and on the camera image.
//  - Per axis: element position readout (mm or deg, the scene's coordinates), state, jog
//    buttons (single steps of the step size at the jog speed), Home, Go to.
//  - Keyboard (panel focused): Left / Right jog the selected axis, Up / Down select the axis,
//    + / - double / halve the step. Esc stops every axis at once (anywhere in the window).
//  - Refusals (soft limits: nothing is sent) and device errors appear in the status line.
//  - Live camera view with crosshair, exposure and gain, and the test pattern the virtual
//    displays show.
//  - Follow gaze: the HOE stages track x_p(alpha) from the analyses (optimiseShift on the
//    traced HOE, tabulated in the background over the gaze range; the geometric guess until
//    it is ready), the micro-OLED x_f(alpha) and the camera the gaze itself, as the gaze
//    sliders (or the scene's eye gaze) move.
//  - Calibration capture wizard (capture_wizard.h).
//
// Threads: the axis workers and the camera loop never touch widgets; their results come
// back as queued calls. The panel owns the LiveBench (devices/bench/live_bench.h).
#include <QPointer>
#include <QWidget>

#include <array>
#include <atomic>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "devices/bench/live_bench.h"
#include "devices/bench/target_follower.h"
#include "widgets/bench/capture_wizard.h"

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QGridLayout;
class QGroupBox;
class QLabel;
class QPushButton;
class QRadioButton;
class QSlider;
class QTimer;
class QButtonGroup;

namespace fovea::widgets {

class SceneDocument;
class CameraView;
class PupilTrackerView;

struct DevicesPanelOptions {
  bool auto_connect = true;               // connect when a scene is opened
  bool allow_hardware = true;             // look for USB controllers and V4L2 cameras
  std::shared_ptr<devices::Clock> clock;  // virtual bench clock (default: real time)
  bool live_camera = true;                // run the camera loop while the panel is visible
  bool analysed_follow = true;            // tabulate x_p(alpha) with the analyses (else geometric only)
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
  // The analyses' x_p(alpha) table (follow gaze) is complete.
  bool followTableReady() const;

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

 protected:
  void keyPressEvent(QKeyEvent* event) override;
  void showEvent(QShowEvent* event) override;
  void hideEvent(QHideEvent* event) override;

 private:
  struct AxisRow {
    devices::AxisWorker* worker = nullptr;
    QString key, unit;
    QRadioButton* select = nullptr;
    QLabel *position = nullptr, *state = nullptr;
    QPushButton *reverse = nullptr, *forward = nullptr, *home = nullptr, *go = nullptr;
    QDoubleSpinBox* target = nullptr;
    std::shared_ptr<std::atomic<int>> pending = std::make_shared<std::atomic<int>>(0);
  };
  void finishConnect(int generation, const std::shared_ptr<std::unique_ptr<devices::LiveBench>>& made,
                     const QString& error, const QString& camera_error);
  void buildAxisRows();
  void clearAxisRows();
  void refresh();
  void submit(const AxisRow& row, const QString& what, std::function<void(devices::Stage&)> command);
  void report(const QString& text, bool error);
  void startCamera();
  void stopCamera();
  void applyExposure();
  void onSceneChanged();
  void startFollowTable();
  void stopFollowTable();
  std::map<devices::GazeFollower::Key, double> followTargets(double yaw, double pitch) const;
  AxisRow* row(const QString& key);
  const AxisRow* row(const QString& key) const;

  SceneDocument* document_;
  DevicesPanelOptions options_;
  std::unique_ptr<devices::LiveBench> live_;
  std::vector<AxisRow> rows_;
  std::vector<std::future<void>> connecting_;
  std::thread connect_thread_;  // builds the LiveBench off the GUI thread
  int connect_generation_ = 0;  // a start whose generation is stale is dropped
  bool want_connected_ = false;

  QLabel* banner_ = nullptr;
  QLabel* status_ = nullptr;
  QPushButton *connect_ = nullptr, *disconnect_ = nullptr, *homeAll_ = nullptr, *estop_ = nullptr;
  QGroupBox* axesBox_ = nullptr;
  QGridLayout* axesGrid_ = nullptr;
  QButtonGroup* selectGroup_ = nullptr;
  QDoubleSpinBox *step_ = nullptr, *speed_ = nullptr;
  QCheckBox* follow_ = nullptr;
  QSlider *gazeYaw_ = nullptr, *gazePitch_ = nullptr;
  QLabel *gazeLabel_ = nullptr, *followInfo_ = nullptr;
  CameraView* camera_view_ = nullptr;
  PupilTrackerView* tracker_ = nullptr;
  QDoubleSpinBox *exposure_ = nullptr, *gain_ = nullptr;
  QCheckBox *crosshair_ = nullptr, *live_check_ = nullptr;
  QComboBox* pattern_ = nullptr;
  QPushButton* wizardButton_ = nullptr;
  QTimer* timer_ = nullptr;
  QPointer<CaptureWizard> wizard_;

  // Camera loop
  std::thread camera_thread_;
  std::atomic<bool> camera_stop_{false};
  std::atomic<bool> frame_pending_{false};

  // Follow gaze
  std::unique_ptr<devices::GazeFollower> follower_;
  std::array<double, 2> gaze_{0.0, 0.0};
  std::array<double, 2> scene_gaze_{0.0, 0.0};
  struct FollowTable {
    std::mutex mutex;
    std::vector<double> gazes;             // yaw = pitch sample angles
    std::vector<double> shift_x, shift_y;  // x_p for yaw, for pitch
    bool ready = false;
  };
  std::shared_ptr<FollowTable> table_;
  bool table_applied_ = false;
  std::thread table_thread_;
  std::shared_ptr<std::atomic<bool>> table_cancel_;
};

}  // namespace fovea::widgets

#pragma once
// The calibration capture wizard: runs a capture plan (devices/calibration/capture_plan.h)
// on the live bench, one step after the other, and keeps everything in a folder
// (devices/calibration/capture_session.h: manifest.json + one PNG per capture, saved after
// every capture).
//
//  - Geometric: checkerboards per micro-OLED position and HOE position over the gaze range.
//  - Colour: the patch sequence on each display; the spectroradiometer's readings are
//    imported as a "fovea-color-measurements" file (checked, copied into the folder).
//  - Gaze: the 5-point fixation sequence; when it is complete the pupil tracker calibrates the
//    gaze on the (virtual) eye camera's frames — both eye cameras on a binocular scene
//    (model/gaze/tracked_calibration.h: 10 samples averaged per target, outliers rejected by detection confidence) and
//    the wizard shows the accuracy and precision reached on the held-out grid and writes them into the manifest.
//
// Pause finishes the running step (a capture is never cut in half) and stops; Resume goes on
// from the first step not captured. Opening a folder that already holds a session of the same
// plan resumes it, so nothing captured is lost across restarts of the studio either.
// Each step runs on a worker thread; the dialog stays responsive and Esc in the main window
// still stops every axis.
#include <QDialog>

#include <array>
#include <atomic>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <utility>

#include "devices/bench/live_bench.h"
#include "devices/calibration/capture_session.h"

#include <nlohmann/json.hpp>
#include "model/scene/scene.h"

class QComboBox;
class QLabel;
class QLineEdit;
class QListWidget;
class QProgressBar;
class QPushButton;

namespace fovea::widgets {

class CaptureWizard : public QDialog {
  Q_OBJECT
 public:
  CaptureWizard(const Scene& scene, devices::LiveBench* live, QWidget* parent = nullptr);
  ~CaptureWizard() override;

  // x_p(alpha) for the geometric plan (the devices panel passes the analyses' table).
  void setHoeShift(std::function<std::array<double, 2>(std::array<double, 2>)> f) { hoe_shift_ = std::move(f); }
  // Where that x_p(alpha) comes from now: (from the gaze study?, description). A geometric
  // session opened before the gaze study is ready says so in a visible warning.
  void setHoeShiftSource(std::function<std::pair<bool, std::string>()> f) { hoe_shift_source_ = std::move(f); }
  // The bench is going away: the running step finishes, nothing more runs.
  void detachBench();
  bool hasBench() const { return live_ != nullptr; }

  void setKind(devices::CaptureKind kind);
  devices::CaptureKind kind() const;
  void setFolder(const QString& folder);
  QString folder() const;

  // Creates (or, when the folder holds one, reopens) the session of the chosen kind.
  bool openSession();
  devices::CaptureSession* session() { return session_.get(); }
  bool isRunning() const { return running_; }
  bool isPaused() const { return !running_ && session_ && !session_->complete(); }
  int capturedCount() const { return captured_; }
  int stepCount() const;
  QStringList skipped() const { return skipped_; }
  bool importMeasurement(const QString& file, QString* error = nullptr);
  // The gaze session's tracked calibration (manifest "gaze_calibration"; on a binocular scene
  // the right eye camera's); null until it ran.
  nlohmann::json gazeCalibration() const;
  // A binocular scene's left eye camera's (manifest "gaze_calibration_left"); null otherwise.
  nlohmann::json leftGazeCalibration() const;
  // Runs the tracked gaze calibration now (a gaze session does it by itself when complete):
  // every eye camera of the scene (model/gaze/eye_tracker_calibration.h).
  void calibrateGaze();

 public slots:
  void start();   // opens the session if needed, then runs from the next step
  void pause();   // after the running step
  void resume();  // = start()

 signals:
  void stepCaptured(int index, const QString& id);
  void runStopped();  // paused, complete, or stopped by an error
  void stepFailed(const QString& message);
  void gazeCalibrated(double accuracy_deg, double precision_deg);  // or stepFailed

 protected:
  void closeEvent(QCloseEvent* event) override;
  void reject() override;  // Esc / close: pause after the running step, then hide

 private:
  void runNext();
  void stepFinished(int index, const QString& error);
  void refreshList();
  void updateButtons();
  QString defaultFolder() const;
  void join();
  void gazeCalibrationFinished(const nlohmann::json& result, const nlohmann::json& left, const QString& error);
  void showGazeCalibration();

  Scene scene_;
  devices::LiveBench* live_;
  std::function<std::array<double, 2>(std::array<double, 2>)> hoe_shift_;
  std::function<std::pair<bool, std::string>()> hoe_shift_source_;
  std::unique_ptr<devices::CaptureSession> session_;
  QStringList skipped_;
  std::thread worker_;
  bool running_ = false;  // a run is in progress (GUI thread)
  std::atomic<bool> pause_requested_{false};
  int captured_ = 0;

  QComboBox* kind_ = nullptr;
  QLineEdit* folder_ = nullptr;
  QPushButton *browse_ = nullptr, *open_ = nullptr, *start_ = nullptr, *pause_ = nullptr, *import_ = nullptr;
  QListWidget* steps_ = nullptr;
  QLabel *instruction_ = nullptr, *thumbnail_ = nullptr, *status_ = nullptr, *hoe_source_ = nullptr,
         *gaze_result_ = nullptr;
  bool calibrating_ = false;
  QProgressBar* progress_ = nullptr;
};

}  // namespace fovea::widgets

#pragma once
// The Bench dock's pupil tracker: the virtual bench's IR eye camera (the eye of the scene at
// the bench's gaze, devices/camera/virtual_eye_renderer.h), the pupil detector and the C.4
// calibration fed by it (model/gaze/tracked_calibration.h), run on a worker thread while
// "Track gaze" is on. The view overlays the detected ellipse (green; amber below the
// calibration's confidence), the glints and the confidence; each tracked gaze is emitted so
// the panel's follow-gaze drives the stages from the tracker instead of the slider. The
// detector combo chooses the classical, learned or auto detector (model/gaze/
// pupil_detector_choice.h) for the calibration and the tracking; changing it while tracking
// recalibrates with the new one.
#include <array>
#include <atomic>
#include <mutex>
#include <optional>
#include <thread>

#include <QWidget>

#include "model/gaze/pupil_detector.h"
#include "model/gaze/pupil_detector_choice.h"
#include "model/scene/scene.h"
#include "widgets/bench/camera_view.h"

class QCheckBox;
class QComboBox;
class QLabel;

namespace fovea::widgets {

// CameraView with the detection drawn over the frame.
class PupilOverlayView : public CameraView {
  Q_OBJECT
 public:
  using CameraView::CameraView;
  void setDetection(const gaze::PupilDetection& d) {
    detection_ = d;
    update();
  }
  const gaze::PupilDetection& detection() const { return detection_; }

 protected:
  void paintEvent(QPaintEvent* event) override;

 private:
  gaze::PupilDetection detection_;
};

class PupilTrackerView : public QWidget {
  Q_OBJECT
 public:
  explicit PupilTrackerView(const Scene& scene, QWidget* parent = nullptr);
  ~PupilTrackerView() override;
  void setEyeGaze(double yaw_deg, double pitch_deg);  // the virtual eye's true gaze
  void setTracking(bool on);
  bool tracking() const;
  void setDetector(gaze::PupilDetectorKind kind);
  gaze::PupilDetectorKind detector() const;
  std::optional<std::array<double, 2>> trackedGaze() const { return tracked_; }
  std::optional<double> calibrationAccuracyDeg() const { return accuracy_; }
  const gaze::PupilDetection& lastDetection() const { return view_->detection(); }

 signals:
  void gazeTracked(double yaw_deg, double pitch_deg, double confidence);

 private:
  void start();
  void stop();
  Scene scene_;
  QCheckBox* track_ = nullptr;
  QComboBox* detector_ = nullptr;
  PupilOverlayView* view_ = nullptr;
  QLabel* info_ = nullptr;
  std::thread worker_;
  std::atomic<bool> stop_{false}, frame_pending_{false};
  std::mutex gaze_mutex_;
  std::array<double, 2> eye_gaze_{0, 0};
  std::optional<std::array<double, 2>> tracked_;
  std::optional<double> accuracy_;
};

}  // namespace fovea::widgets

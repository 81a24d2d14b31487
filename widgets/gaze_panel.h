#pragma once
// Gaze dock: yaw and pitch sliders (with spin boxes) that set the scene's eye.gaze_deg —
// one undo step per slider drag — and the "HOE follows gaze" toggle, with a read-out of the
// live trace: the applied HOE travel x_p, the FOV, efficiency and rays in the pupil.

#include <QWidget>

#include <memory>

#include "widgets/live_trace.h"

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QSlider;

namespace fovea::widgets {

class SceneDocument;

class GazePanel : public QWidget {
  Q_OBJECT
 public:
  explicit GazePanel(SceneDocument* document, QWidget* parent = nullptr);

  QSlider* yawSlider() const { return yaw_; }
  QSlider* pitchSlider() const { return pitch_; }
  QCheckBox* followToggle() const { return follow_; }
  // A slider is held (its drag asks for coarse traces, widgets/live_trace.h).
  bool isDragging() const;
  bool followGaze() const;
  void setFollowGaze(bool on);
  // Sets the gaze (degrees) as the sliders would: one undoable edit.
  void setGaze(double yaw_deg, double pitch_deg);

  void showResult(const std::shared_ptr<const LiveTraceResult>& result, bool busy);

  static constexpr int kStepsPerDegree = 2;  // slider resolution: 0.5 deg

 signals:
  void followGazeChanged(bool on);

 private:
  void refreshFromScene();
  void commitGaze(double yaw, double pitch);

  SceneDocument* document_;
  QSlider* yaw_ = nullptr;
  QSlider* pitch_ = nullptr;
  QDoubleSpinBox* yawSpin_ = nullptr;
  QDoubleSpinBox* pitchSpin_ = nullptr;
  QCheckBox* follow_ = nullptr;
  QComboBox* xpRule_ = nullptr;
  QLabel* readout_ = nullptr;
  int gesture_ = -1;  // merge id of the slider drag in progress (-1: none)
  bool refreshing_ = false;
};

}  // namespace fovea::widgets

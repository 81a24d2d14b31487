#pragma once
// Gaze dock: yaw and pitch sliders (with spin boxes) that set the scene's eye.gaze_deg —
// one undo step per slider drag — and the "HOE follows gaze" toggle, with a read-out of the
// live trace: the applied HOE travel x_p, the FOV, efficiency and rays in the pupil.
//
// On a binocular scene (issue 30 item 5) a fixation distance (30-250 cm, or off) joins the
// gaze: with it on, yaw and pitch are the direction of the fixation point seen from midway
// between the eyes, and the scene gets the right eye's gaze fixating that point
// (model/gaze/fixation_gazes.h gazesFixating) and the distance (binocular.fixation_distance_mm,
// from which eye_scene.h derives the left eye's gaze). A read-out gives the vergence angle
// and both gazes, and a top view (widgets/binocular_top_view.h) draws them. Off: the
// sliders set the right eye's gaze, the left eye's is its mirror (as before). Hidden on a
// monocular scene.

#include <QWidget>

#include <array>
#include <memory>
#include <optional>

#include "widgets/live_trace.h"

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QSlider;

namespace fovea::widgets {

class BinocularTopView;
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

  // Binocular scenes: the fixation distance in cm (nullopt: off), set as the control does
  // (one undoable edit). The controls and the top view.
  void setFixationDistanceCm(std::optional<double> cm);
  QCheckBox* fixationToggle() const { return fixationOn_; }
  QDoubleSpinBox* fixationSpin() const { return fixationCm_; }
  QLabel* fixationReadout() const { return fixationReadout_; }
  BinocularTopView* topView() const { return topView_; }
  static constexpr double kMinFixationCm = 30.0, kMaxFixationCm = 250.0;  // seed C.3

  static constexpr int kStepsPerDegree = 2;  // slider resolution: 0.5 deg

 signals:
  void followGazeChanged(bool on);

 private:
  void refreshFromScene();
  void commitGaze(double yaw, double pitch);
  void commitFixation(std::optional<double> cm);
  // The fixation distance the scene holds (mm), 0 when off or monocular.
  double fixationMm() const;
  // What the sliders show: the fixation direction with a fixation distance, else the gaze.
  std::array<double, 2> shownGaze() const;
  void refreshBinocular();

  SceneDocument* document_;
  QSlider* yaw_ = nullptr;
  QSlider* pitch_ = nullptr;
  QDoubleSpinBox* yawSpin_ = nullptr;
  QDoubleSpinBox* pitchSpin_ = nullptr;
  QCheckBox* follow_ = nullptr;
  QComboBox* xpRule_ = nullptr;
  QLabel* readout_ = nullptr;
  QWidget* binocularBox_ = nullptr;  // the fixation controls, read-out and top view
  QCheckBox* fixationOn_ = nullptr;
  QDoubleSpinBox* fixationCm_ = nullptr;
  QLabel* fixationReadout_ = nullptr;
  BinocularTopView* topView_ = nullptr;
  int gesture_ = -1;  // merge id of the slider drag in progress (-1: none)
  bool refreshing_ = false;
};

}  // namespace fovea::widgets

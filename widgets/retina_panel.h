#pragma once
// The Retina dock's content: the retina view (widgets/retina_view.h) with, on a binocular
// scene (issue 30 item 5), a selector of the eye it shows. The right eye is the scene's own
// trace; the left eye's is the trace of eyeScene(scene, Left) (model/scene/eye_scene.h) at the
// left eye's gaze, which the studio runs only while the left eye is shown. Hidden selector on
// a monocular scene (the right, the only, eye).

#include <QWidget>

#include "model/scene/eye_scene.h"

class QComboBox;

namespace fovea::widgets {

class RetinaView;

class RetinaPanel : public QWidget {
  Q_OBJECT
 public:
  explicit RetinaPanel(QWidget* parent = nullptr);

  RetinaView* view() const { return view_; }
  QComboBox* eyeSelector() const { return eye_; }
  void setBinocular(bool on);
  // The eye shown (Right on a monocular scene).
  EyeSide eye() const;
  void setEye(EyeSide side);

 signals:
  void eyeChanged(fovea::EyeSide side);

 private:
  RetinaView* view_ = nullptr;
  QWidget* eyeRow_ = nullptr;
  QComboBox* eye_ = nullptr;
};

}  // namespace fovea::widgets

#include "widgets/retina_panel.h"

#include <QComboBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QVBoxLayout>

#include "widgets/retina_view.h"

namespace fovea::widgets {

RetinaPanel::RetinaPanel(QWidget* parent) : QWidget(parent) {
  setObjectName("RetinaPanel");
  auto* box = new QVBoxLayout(this);
  box->setContentsMargins(0, 0, 0, 0);
  box->setSpacing(2);
  eyeRow_ = new QWidget(this);
  auto* row = new QHBoxLayout(eyeRow_);
  row->setContentsMargins(6, 4, 6, 0);
  eye_ = new QComboBox(eyeRow_);
  eye_->setObjectName("retinaEye");
  eye_->addItem(tr("Right eye"), int(EyeSide::Right));
  eye_->addItem(tr("Left eye"), int(EyeSide::Left));
  eye_->setToolTip(
      tr("The eye whose retina is shown: the right eye is the scene's train, the left eye its "
         "binocular partner at its own gaze (as fovea-cli --eye left)"));
  auto* label = new QLabel(tr("Eye"), eyeRow_);
  label->setBuddy(eye_);
  row->addWidget(label);
  row->addWidget(eye_);
  row->addStretch(1);
  box->addWidget(eyeRow_);
  view_ = new RetinaView(this);
  view_->setObjectName("RetinaView");
  box->addWidget(view_, 1);
  eyeRow_->setVisible(false);
  connect(eye_, &QComboBox::currentIndexChanged, this, [this] { emit eyeChanged(eye()); });
}

void RetinaPanel::setBinocular(bool on) {
  eyeRow_->setVisible(on);
  if (!on && eye() != EyeSide::Right) setEye(EyeSide::Right);
}

EyeSide RetinaPanel::eye() const {
  return eyeRow_->isVisibleTo(this) && eye_->currentData().toInt() == int(EyeSide::Left) ? EyeSide::Left
                                                                                         : EyeSide::Right;
}

void RetinaPanel::setEye(EyeSide side) {
  eye_->setCurrentIndex(eye_->findData(int(side)));
}

}  // namespace fovea::widgets

#include "widgets/retina_image_controls.h"

#include <QComboBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QSignalBlocker>
#include <QSpinBox>

namespace fovea::widgets {

RetinaImageControls::RetinaImageControls(QWidget* parent) : QWidget(parent) {
  setObjectName("RetinaImageControls");
  auto* row = new QHBoxLayout(this);
  row->setContentsMargins(0, 0, 0, 0);
  row->setSpacing(4);  // five controls in the dock's minimum width (tst_preview_retina_options)
  speckle_ = new QSpinBox(this);
  speckle_->setObjectName("RetinaSpeckle");
  speckle_->setRange(0, kMaxSpecklePatterns);
  speckle_->setSpecialValueText(tr("off"));
  speckle_->setToolTip(
      tr("Speckle: independent speckle patterns per laser (off: none); the image's speckle contrast falls as "
         "1/sqrt(patterns x lasers) (fovea-cli retina-image --speckle N)"));
  grain_ = new QComboBox(this);
  grain_->setObjectName("RetinaSpeckleGrain");
  grain_->addItem(tr("pixel"));
  grain_->addItem(tr("pupil"));
  grain_->setToolTip(
      tr("Speckle grain: one canvas pixel, or the pupil's Airy grain integrated over each pixel "
         "(--speckle-grain pixel|pupil)"));
  seed_ = new QSpinBox(this);
  seed_->setObjectName("RetinaSpeckleSeed");
  seed_->setRange(1, kMaxSpeckleSeed);
  seed_->setValue(1);
  seed_->setToolTip(
      tr("Speckle seed (1-999): another seed draws other, equally likely speckle patterns; the same seed gives the "
         "same image (fovea-cli retina-image --seed S, report --retina-seed S)"));
  calibration_ = new QComboBox(this);
  calibration_->setObjectName("RetinaCalibration");
  calibration_->addItem(tr("one warp"));  // short: the row fits the dock at 1366 x 768
  calibration_->addItem(tr("per laser"));
  calibration_->setToolTip(
      tr("Lateral colour: one geometric calibration for all lasers, measured on the laser nearest 555 nm (each "
         "layer's dispersion shows as colour fringes), or each laser warped on its own (no lateral colour; "
         "--per-laser-calibration)"));
  auto* speckleLabel = new QLabel(tr("Speckle"), this);
  speckleLabel->setBuddy(speckle_);
  speckleLabel->setToolTip(speckle_->toolTip());
  row->addWidget(speckleLabel);
  row->addWidget(speckle_);
  row->addWidget(grain_);
  row->addWidget(seed_);
  row->addWidget(calibration_, 1);
  grain_->setEnabled(false);
  seed_->setEnabled(false);
  connect(speckle_, &QSpinBox::valueChanged, this, [this](int n) {
    grain_->setEnabled(n > 0);
    seed_->setEnabled(n > 0);
    emit changed();
  });
  connect(grain_, &QComboBox::currentIndexChanged, this, [this] {
    if (speckle_->value() > 0) emit changed();
  });
  connect(seed_, &QSpinBox::valueChanged, this, [this] {
    if (speckle_->value() > 0) emit changed();
  });
  connect(calibration_, &QComboBox::currentIndexChanged, this, &RetinaImageControls::changed);
}

RetinaPreviewOptions RetinaImageControls::options() const {
  return {speckle_->value(), grain_->currentIndex() == 1, calibration_->currentIndex() == 1, seed_->value()};
}

void RetinaImageControls::setOptions(const RetinaPreviewOptions& o) {
  if (o == options()) return;
  {
    const QSignalBlocker b1(speckle_), b2(grain_), b3(calibration_), b4(seed_);
    speckle_->setValue(o.speckle_patterns);
    grain_->setCurrentIndex(o.speckle_grain_pupil ? 1 : 0);
    calibration_->setCurrentIndex(o.per_laser_calibration ? 1 : 0);
    seed_->setValue(o.speckle_seed);
    grain_->setEnabled(speckle_->value() > 0);
    seed_->setEnabled(speckle_->value() > 0);
  }
  emit changed();
}

}  // namespace fovea::widgets

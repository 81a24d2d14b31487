#include "widgets/bench/eye_camera_box.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QVBoxLayout>

#include <chrono>

#include "devices/calibration/capture_plan.h"
#include "widgets/bench/camera_view.h"

namespace fovea::widgets {

EyeCameraBox::EyeCameraBox(std::function<Scene()> scene, bool live_by_default, QWidget* parent)
    : QGroupBox(tr("Eye camera"), parent), scene_(std::move(scene)) {
  auto* cl = new QVBoxLayout(this);
  cl->setContentsMargins(4, 4, 4, 4);
  view_ = new CameraView(this);
  cl->addWidget(view_, 1);
  auto* controls = new QHBoxLayout;
  live_check_ = new QCheckBox(tr("Live"), this);
  live_check_->setObjectName("cameraLive");
  live_check_->setChecked(live_by_default);
  crosshair_ = new QCheckBox(tr("Crosshair"), this);
  crosshair_->setChecked(true);
  controls->addWidget(live_check_);
  controls->addWidget(crosshair_);
  controls->addWidget(new QLabel(tr("Exposure"), this));
  exposure_ = new QDoubleSpinBox(this);
  exposure_->setObjectName("cameraExposure");
  exposure_->setRange(0.1, 1000.0);
  exposure_->setDecimals(1);
  exposure_->setValue(10.0);
  exposure_->setSuffix(tr(" ms"));
  controls->addWidget(exposure_);
  controls->addWidget(new QLabel(tr("Gain"), this));
  gain_ = new QDoubleSpinBox(this);
  gain_->setObjectName("cameraGain");
  gain_->setRange(0.1, 64.0);
  gain_->setDecimals(1);
  gain_->setValue(1.0);
  controls->addWidget(gain_);
  controls->addStretch();
  cl->addLayout(controls);
  auto* patternRow = new QHBoxLayout;
  patternRow->addWidget(new QLabel(tr("Displays show"), this));
  pattern_ = new QComboBox(this);
  pattern_->setObjectName("testPattern");
  pattern_->addItems({tr("nothing"), tr("checkerboards (both)"), tr("projector checkerboard"),
                      tr("micro-OLED checkerboard"), tr("white (both)")});
  pattern_->setCurrentIndex(1);
  pattern_->setToolTip(tr("Test pattern of the virtual displays"));
  patternRow->addWidget(pattern_, 1);
  cl->addLayout(patternRow);
  connect(crosshair_, &QCheckBox::toggled, view_, &CameraView::setCrosshair);
  connect(exposure_, &QDoubleSpinBox::valueChanged, this, [this] { applyExposure(); });
  connect(gain_, &QDoubleSpinBox::valueChanged, this, [this] { applyExposure(); });
  connect(pattern_, &QComboBox::currentIndexChanged, this, &EyeCameraBox::setTestPattern);
  connect(live_check_, &QCheckBox::toggled, this, &EyeCameraBox::liveToggled);
}

EyeCameraBox::~EyeCameraBox() {
  stop();
}

void EyeCameraBox::setBench(devices::LiveBench* live) {
  stop();
  live_ = live;
  if (!live_) {
    view_->setFrame({}, {});
    view_->setBanner({});
    return;
  }
  setTestPattern(pattern_->currentIndex());
  applyExposure();
}

bool EyeCameraBox::liveChecked() const {
  return live_check_->isChecked();
}

bool EyeCameraBox::hasFrame() const {
  return !view_->frame().isNull();
}

int EyeCameraBox::testPattern() const {
  return pattern_->currentIndex();
}

void EyeCameraBox::setBanner(const QString& text) {
  view_->setBanner(text);
}

void EyeCameraBox::start() {
  if (!live_ || !live_check_->isChecked() || thread_.joinable()) return;
  stop_ = false;
  devices::Camera* cam = &live_->camera();
  thread_ = std::thread([this, cam] {
    using clock = std::chrono::steady_clock;
    while (!stop_) {
      const auto t0 = clock::now();
      if (!frame_pending_) {
        try {
          const devices::Frame f = cam->grab();
          QImage img(f.image.data, f.image.cols, f.image.rows, static_cast<int>(f.image.step),
                     QImage::Format_Grayscale8);
          const QString caption = QString::fromStdString(cam->info().model) + tr("  #%1  t=%2 s  exp %3 ms")
                                                                                  .arg(f.sequence)
                                                                                  .arg(f.exposure_start_s, 0, 'f', 2)
                                                                                  .arg(f.exposure_s * 1e3, 0, 'f', 1);
          frame_pending_ = true;
          QMetaObject::invokeMethod(
              this,
              [this, img = img.copy(), caption] {
                view_->setFrame(img, caption);
                frame_pending_ = false;
              },
              Qt::QueuedConnection);
        } catch (const std::exception& e) {
          const QString msg = QString::fromStdString(e.what());
          QMetaObject::invokeMethod(
              this, [this, msg] { emit report(tr("Camera: %1").arg(msg), true); }, Qt::QueuedConnection);
          for (int i = 0; i < 20 && !stop_; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(50));
        }
      }
      // About 10 frames per second for the live view.
      const auto next = t0 + std::chrono::milliseconds(100);
      while (!stop_ && clock::now() < next) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  });
}

void EyeCameraBox::stop() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
  frame_pending_ = false;
}

void EyeCameraBox::applyExposure() {
  if (!live_) return;
  devices::Camera& c = live_->camera();
  try {
    if (c.hasExposure()) c.setExposure(exposure_->value() * 1e-3);
    if (c.hasGain()) c.setGain(gain_->value());
  } catch (const std::exception& e) {
    emit report(tr("Camera: %1").arg(QString::fromStdString(e.what())), true);
  }
  exposure_->setEnabled(c.hasExposure());
  gain_->setEnabled(c.hasGain());
}

void EyeCameraBox::setTestPattern(int index) {
  if (pattern_->currentIndex() != index) {
    pattern_->setCurrentIndex(index);  // re-enters through the signal
    return;
  }
  if (!live_ || !live_->optics()) return;
  const Scene scene = scene_ ? scene_() : Scene{};
  auto* o = live_->optics();
  const auto board_p = devices::peripheralBoard(scene);
  const auto board_f = devices::fovealBoard(scene);
  const auto off = image::offPattern();
  const auto white = image::flatPatch({1, 1, 1});
  switch (index) {
    case 1:
      o->show(BenchDisplay::Peripheral, board_p);
      o->show(BenchDisplay::Foveal, board_f);
      break;
    case 2:
      o->show(BenchDisplay::Peripheral, board_p);
      o->show(BenchDisplay::Foveal, off);
      break;
    case 3:
      o->show(BenchDisplay::Peripheral, off);
      o->show(BenchDisplay::Foveal, board_f);
      break;
    case 4:
      o->show(BenchDisplay::Peripheral, white);
      o->show(BenchDisplay::Foveal, white);
      break;
    default:
      o->show(BenchDisplay::Peripheral, off);
      o->show(BenchDisplay::Foveal, off);
  }
}

}  // namespace fovea::widgets

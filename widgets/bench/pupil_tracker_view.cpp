#include "widgets/bench/pupil_tracker_view.h"

#include <QCheckBox>
#include <QComboBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QPainter>
#include <QVBoxLayout>

#include <chrono>

#include "devices/camera/virtual_eye_renderer.h"
#include "devices/virtual/sim_clock.h"
#include "model/gaze/tracked_calibration.h"

namespace fovea::widgets {

void PupilOverlayView::paintEvent(QPaintEvent* event) {
  CameraView::paintEvent(event);
  const QImage& img = frame();
  if (img.isNull()) return;
  const QSizeF s = QSizeF(img.size()).scaled(size(), Qt::KeepAspectRatio);
  const QRectF target(QPointF((width() - s.width()) / 2, (height() - s.height()) / 2), s);
  const double k = target.width() / img.width();
  const auto toView = [&](const cv::Point2d& p) {
    return QPointF(target.left() + (p.x + 0.5) * k, target.top() + (p.y + 0.5) * k);
  };
  QPainter p(this);
  p.setRenderHint(QPainter::Antialiasing);
  const auto& d = detection_;
  if (d.found) {
    p.save();
    p.translate(toView(d.ellipse.centre));
    p.rotate(d.ellipse.angle_deg);
    p.setPen(QPen(d.confidence >= 0.6 ? QColor(60, 220, 60) : QColor(240, 170, 0), 2));
    p.drawEllipse(QPointF(0, 0), d.ellipse.major_px / 2 * k, d.ellipse.minor_px / 2 * k);
    p.drawLine(QPointF(-4, 0), QPointF(4, 0));
    p.drawLine(QPointF(0, -4), QPointF(0, 4));
    p.restore();
  }
  p.setPen(QPen(QColor(0, 200, 255), 1.5));
  for (const auto& g : d.glints_px) p.drawEllipse(toView(g), 4, 4);
  const QString text = d.found ? tr("confidence %1").arg(d.confidence, 0, 'f', 2)
                               : tr("no pupil (%1)").arg(QString::fromStdString(d.reason));
  const QRect r = p.fontMetrics().boundingRect(text).adjusted(-4, -2, 4, 2);
  const QRect box(width() - r.width() - 4, 4, r.width(), r.height());
  p.fillRect(box, QColor(0, 0, 0, 170));
  p.setPen(d.found ? Qt::white : QColor(255, 120, 120));
  p.drawText(box, Qt::AlignCenter, text);
}

PupilTrackerView::PupilTrackerView(const Scene& scene, QWidget* parent) : QWidget(parent), scene_(scene) {
  setObjectName("PupilTrackerView");
  auto* l = new QVBoxLayout(this);
  l->setContentsMargins(0, 0, 0, 0);
  track_ = new QCheckBox(tr("Track gaze (virtual IR eye camera → pupil → C.4 map → follow gaze)"), this);
  track_->setObjectName("trackGaze");
  view_ = new PupilOverlayView(this);
  view_->setCrosshair(false);
  view_->setBanner(tr("VIRTUAL"));
  info_ = new QLabel(tr("Tracking off"), this);
  info_->setObjectName("trackInfo");
  info_->setWordWrap(true);
  detector_ = new QComboBox(this);
  detector_->setObjectName("pupilDetector");
  for (auto k : {gaze::PupilDetectorKind::Classical, gaze::PupilDetectorKind::Learned, gaze::PupilDetectorKind::Auto})
    detector_->addItem(QString::fromLatin1(gaze::detectorName(k)), static_cast<int>(k));
  detector_->setToolTip(
      tr("Pupil detector: classical (ellipse fit), learned (CNN, resources/pupil/pupil-net.onnx) "
         "or auto (learned proposal refined by the classical fit)"));
  auto* row = new QHBoxLayout;
  row->addWidget(track_, 1);
  row->addWidget(new QLabel(tr("Detector:"), this));
  row->addWidget(detector_);
  l->addLayout(row);
  l->addWidget(view_, 1);
  l->addWidget(info_);
  connect(track_, &QCheckBox::toggled, this, [this](bool on) { on ? start() : stop(); });
  connect(detector_, &QComboBox::currentIndexChanged, this, [this] {
    if (!tracking()) return;
    stop();
    start();
  });
}

void PupilTrackerView::setDetector(gaze::PupilDetectorKind kind) {
  detector_->setCurrentIndex(detector_->findData(static_cast<int>(kind)));
}

gaze::PupilDetectorKind PupilTrackerView::detector() const {
  return static_cast<gaze::PupilDetectorKind>(detector_->currentData().toInt());
}

PupilTrackerView::~PupilTrackerView() {
  stop();
}

void PupilTrackerView::setEyeGaze(double yaw_deg, double pitch_deg) {
  std::lock_guard lock(gaze_mutex_);
  eye_gaze_ = {yaw_deg, pitch_deg};
}

void PupilTrackerView::setTracking(bool on) {
  track_->setChecked(on);
}

bool PupilTrackerView::tracking() const {
  return track_->isChecked();
}

void PupilTrackerView::start() {
  if (worker_.joinable()) return;
  stop_ = false;
  info_->setText(tr("Calibrating (5 targets x 10 samples)…"));
  const gaze::PupilDetectorKind kind = detector();
  worker_ = std::thread([this, kind] {
    gaze::TrackedCalibrationOptions co;
    co.detector_kind = kind;
    co.eye.pupil_diameter_mm = scene_.eye.pupil_diameter_mm;
    gaze::GazeCalibrationResult cal;
    try {
      cal = gaze::calibrateWithTracker(co).result;
    } catch (const std::exception& e) {
      const QString msg = QString::fromStdString(e.what());
      QMetaObject::invokeMethod(this, [this, msg] { info_->setText(tr("Calibration failed: %1").arg(msg)); });
      return;
    }
    const double accuracy = cal.accuracy_mean_deg, precision = cal.precision_rms_s2s_deg;
    QMetaObject::invokeMethod(this, [this, accuracy] { accuracy_ = accuracy; });
    auto clock = std::make_shared<devices::SteadyClock>();
    devices::VirtualCamera cam(clock,
                               devices::virtualEyeRenderer(scene_,
                                                           [this](double) {
                                                             std::lock_guard lock(gaze_mutex_);
                                                             return eye_gaze_;
                                                           }),
                               co.camera.size, 30.0, 7);
    cam.open();
    using steady = std::chrono::steady_clock;
    while (!stop_) {
      const auto t0 = steady::now();
      if (!frame_pending_) {
        const devices::Frame f = cam.grab();
        const auto d0 = steady::now();
        gaze::PupilDetection d;
        try {
          d = gaze::detectPupilWith(kind, f.image);
        } catch (const std::exception& e) {  // the learned model went missing after the calibration
          const QString msg = QString::fromStdString(e.what());
          QMetaObject::invokeMethod(this, [this, msg] { info_->setText(tr("Detector failed: %1").arg(msg)); });
          return;
        }
        const double ms = std::chrono::duration<double, std::milli>(steady::now() - d0).count();
        std::optional<std::array<double, 2>> g;
        if (d.found && d.confidence >= co.min_confidence) g = cal.map.gazeDeg({d.ellipse.centre.x, d.ellipse.centre.y});
        QImage img(f.image.data, f.image.cols, f.image.rows, static_cast<int>(f.image.step), QImage::Format_Grayscale8);
        frame_pending_ = true;
        QMetaObject::invokeMethod(
            this,
            [this, img = img.copy(), d, g, ms, accuracy, precision, seq = f.sequence] {
              view_->setFrame(img, tr("virtual IR eye camera  #%1  detect %2 ms").arg(seq).arg(ms, 0, 'f', 2));
              view_->setDetection(d);
              tracked_ = g;
              info_->setText(tr("Calibration: accuracy %1°, precision %2° (held-out targets).  Tracked gaze: %3")
                                 .arg(accuracy, 0, 'f', 2)
                                 .arg(precision, 0, 'f', 2)
                                 .arg(g ? tr("%1°, %2°").arg((*g)[0], 0, 'f', 2).arg((*g)[1], 0, 'f', 2) : tr("none")));
              if (g) emit gazeTracked((*g)[0], (*g)[1], d.confidence);
              frame_pending_ = false;
            },
            Qt::QueuedConnection);
      }
      const auto next = t0 + std::chrono::milliseconds(100);
      while (!stop_ && steady::now() < next) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  });
}

void PupilTrackerView::stop() {
  stop_ = true;
  if (worker_.joinable()) worker_.join();
  frame_pending_ = false;
  if (info_) info_->setText(tr("Tracking off"));
}

}  // namespace fovea::widgets

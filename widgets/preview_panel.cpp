#include "widgets/preview_panel.h"

#include <QCheckBox>
#include <QFileDialog>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QPainter>
#include <QPushButton>
#include <QSlider>
#include <QTimer>
#include <QVBoxLayout>

#include <chrono>
#include <cmath>
#include <memory>

#include <opencv2/imgproc.hpp>

#include "model/color/srgb.h"
#include "model/image/foveation.h"
#include "model/image/image_io.h"
#include "model/image/test_target.h"
#include "model/scene/scene_compare.h"
#include "widgets/dialog_start.h"
#include "widgets/scene_document.h"

namespace fovea::widgets {

namespace {
constexpr int kStepsPerDeg = 4;  // slider resolution: 0.25 deg
constexpr int kViewWidthPx = 640;

// Linear RGB -> 8-bit sRGB QImage, area-downsampled to at most `max_width` pixels wide.
QImage toQImage(const cv::Mat& linear, int max_width) {
  if (linear.empty()) return {};
  cv::Mat small = linear;
  if (linear.cols > max_width) {
    const int h = std::max(1, static_cast<int>(std::lround(linear.rows * double(max_width) / linear.cols)));
    cv::resize(linear, small, cv::Size(max_width, h), 0, 0, cv::INTER_AREA);
  }
  static const std::vector<uchar> lut = [] {
    std::vector<uchar> t(4097);
    for (int i = 0; i <= 4096; ++i)
      t[i] = static_cast<uchar>(std::lround(255.0 * color::linearToSrgb(static_cast<float>(i) / 4096.0f)));
    return t;
  }();
  QImage out(small.cols, small.rows, QImage::Format_RGB888);
  for (int y = 0; y < small.rows; ++y) {
    const auto* in = small.ptr<cv::Vec3f>(y);
    uchar* o = out.scanLine(y);
    for (int x = 0; x < small.cols; ++x)
      for (int c = 0; c < 3; ++c) o[3 * x + c] = lut[static_cast<int>(std::clamp(in[x][c], 0.0f, 1.0f) * 4096.0f)];
  }
  return out;
}
}  // namespace

// Lives on the panel's worker thread; the panel talks to it only through queued calls.
class PreviewWorker : public QObject {
 public:
  explicit PreviewWorker(PreviewPanel* panel) : panel_(panel) {}

  void configure(const Scene& scene, bool blend) {
    scene_ = scene;
    compositor_ = std::make_unique<image::FoveatedCompositor>(scene, blend);
    if (target_.empty()) {
      const image::DisplayAngles a = image::displayAngles(scene);
      setTarget(image::makeTestTarget({1920, 1080}, a.peripheral_fov_deg, 20.0));
    } else {
      compositor_->setTarget(target_);
    }
  }
  void setTarget(const cv::Mat& target) {
    target_ = target;
    targetImage_ = toQImage(target_, kViewWidthPx);
    if (compositor_) compositor_->setTarget(target_);
  }
  void loadTarget(const QString& path) {
    try {
      setTarget(image::readLinearRgb(path.toStdString()));
    } catch (const image::ImageIoError& e) {
      error_ = QString::fromStdString(e.what());
    }
  }
  void render(std::array<double, 2> gaze, bool seam, int generation) {
    PreviewFrame f;
    f.generation = generation;
    f.error = error_;
    error_.clear();
    if (compositor_) {
      const auto t0 = std::chrono::steady_clock::now();
      compositor_->update(gaze);
      f.update_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      if (seam) f.seam_flip = compositor_->seamMetric().mean_flip;
      f.gaze_deg = gaze;
      f.target = targetImage_;
      f.foveal = toQImage(compositor_->fovealImage(), kViewWidthPx);
      f.peripheral = toQImage(compositor_->peripheralImage(), kViewWidthPx);
      f.perceived = toQImage(compositor_->perceivedImage(), kViewWidthPx);
      f.target_fov_deg = compositor_->angles().peripheral_fov_deg;
      f.foveal_fov_deg = compositor_->angles().foveal_fov_deg;
      const auto& p = compositor_->profile();
      f.ring_deg = {p.blur_start_deg, p.blend_start_deg, p.blend_end_deg};
    }
    QPointer<PreviewPanel> panel = panel_;
    QMetaObject::invokeMethod(
        panel_,
        [panel, f] {
          if (panel) panel->showFrame(f);
        },
        Qt::QueuedConnection);
  }

 private:
  PreviewPanel* panel_;
  Scene scene_;
  cv::Mat target_;
  QImage targetImage_;
  QString error_;
  std::unique_ptr<image::FoveatedCompositor> compositor_;
};

PreviewImageView::PreviewImageView(const QString& title, QWidget* parent) : QWidget(parent), title_(title) {
  setMinimumSize(160, 110);
  QSizePolicy policy(QSizePolicy::Expanding, QSizePolicy::Preferred);
  policy.setHeightForWidth(true);
  setSizePolicy(policy);
}

int PreviewImageView::heightForWidth(int width) const {
  const double aspect = image_.isNull() ? 9.0 / 16.0 : double(image_.height()) / image_.width();
  return fontMetrics().height() + 4 + static_cast<int>(std::lround(width * aspect));
}

void PreviewImageView::setImage(const QImage& image) {
  image_ = image;
  scaled_ = QImage();
  update();
}

void PreviewImageView::setRings(std::array<double, 2> fov, std::array<double, 2> centre, std::vector<double> radii) {
  fov_ = fov;
  centre_ = centre;
  radii_ = std::move(radii);
  update();
}

void PreviewImageView::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.fillRect(rect(), palette().window());
  const int titleH = fontMetrics().height() + 4;
  p.drawText(QRect(0, 0, width(), titleH), Qt::AlignLeft | Qt::AlignVCenter, title_);
  if (image_.isNull()) return;
  const QRect area(0, titleH, width(), height() - titleH);
  QSize s = image_.size();
  s.scale(area.size(), Qt::KeepAspectRatio);
  const QRect target(area.x() + (area.width() - s.width()) / 2, area.y(), s.width(), s.height());
  // Area-averaged downscale (QImage::scaled smooth), not the painter's bilinear one,
  // which aliases fine patterns into false rings.
  if (scaled_.size() != s) scaled_ = image_.scaled(s, Qt::IgnoreAspectRatio, Qt::SmoothTransformation);
  p.drawImage(target.topLeft(), scaled_);
  if (fov_[0] <= 0 || radii_.empty()) return;
  // Rings at the blending radii, in the image's equal-angle coordinates.
  p.setRenderHint(QPainter::Antialiasing);
  const double sx = target.width() / fov_[0], sy = target.height() / fov_[1];
  const QPointF c(target.x() + (centre_[0] / fov_[0] + 0.5) * target.width(),
                  target.y() + (0.5 - centre_[1] / fov_[1]) * target.height());
  const QColor colours[3] = {QColor(255, 220, 0), QColor(255, 120, 0), QColor(255, 40, 40)};
  for (std::size_t i = 0; i < radii_.size(); ++i) {
    p.setPen(QPen(colours[std::min<std::size_t>(i, 2)], 1.0, Qt::DashLine));
    p.drawEllipse(c, radii_[i] * sx, radii_[i] * sy);
  }
  p.setPen(QPen(Qt::white, 1.0));
  p.drawLine(c - QPointF(4, 0), c + QPointF(4, 0));
  p.drawLine(c - QPointF(0, 4), c + QPointF(0, 4));
}

PreviewPanel::PreviewPanel(SceneDocument* document, QWidget* parent) : QWidget(parent), document_(document) {
  setObjectName("PreviewPanel");
  auto* layout = new QVBoxLayout(this);
  auto* top = new QHBoxLayout;
  auto* open = new QPushButton(tr("Target…"), this);
  open->setToolTip(tr("Load a target image (PNG, JPEG, TIFF, EXR…) covering the peripheral FOV"));
  blend_ = new QCheckBox(tr("Blend (B.2.3)"), this);
  blend_->setChecked(true);
  blend_->setToolTip(tr("Blur ramp and crossfade; off: a hard switch at the blend start angle"));
  status_ = new QLabel(this);
  status_->setObjectName("PreviewStatus");
  top->addWidget(open);
  top->addWidget(blend_);
  top->addWidget(status_, 1);
  layout->addLayout(top);

  auto slider = [this](const QString& name, QLabel*& label) {
    auto* row = new QHBoxLayout;
    auto* s = new QSlider(Qt::Horizontal, this);
    s->setObjectName(name);
    label = new QLabel(this);
    label->setMinimumWidth(110);
    row->addWidget(label);
    row->addWidget(s, 1);
    static_cast<QVBoxLayout*>(this->layout())->addLayout(row);
    return s;
  };
  yaw_ = slider("GazeYaw", yawLabel_);
  pitch_ = slider("GazePitch", pitchLabel_);

  auto* grid = new QGridLayout;
  targetView_ = new PreviewImageView(tr("Target"), this);
  fovealView_ = new PreviewImageView(tr("Foveal (micro-OLED)"), this);
  peripheralView_ = new PreviewImageView(tr("Peripheral (projector)"), this);
  perceivedView_ = new PreviewImageView(tr("Perceived"), this);
  grid->addWidget(targetView_, 0, 0);
  grid->addWidget(fovealView_, 0, 1);
  grid->addWidget(peripheralView_, 1, 0);
  grid->addWidget(perceivedView_, 1, 1);
  layout->addLayout(grid);
  layout->addStretch(1);

  seamTimer_ = new QTimer(this);
  seamTimer_->setSingleShot(true);
  seamTimer_->setInterval(300);
  connect(seamTimer_, &QTimer::timeout, this, [this] { requestRender(true); });

  worker_ = new PreviewWorker(this);
  worker_->moveToThread(&thread_);
  connect(&thread_, &QThread::finished, worker_, &QObject::deleteLater);
  thread_.setObjectName("PreviewWorker");
  thread_.start();

  auto gazeMoved = [this] {
    const auto g = gaze();
    yawLabel_->setText(tr("yaw %1°").arg(g[0], 0, 'f', 2));
    pitchLabel_->setText(tr("pitch %1°").arg(g[1], 0, 'f', 2));
    requestRender(false);
    seamTimer_->start();
  };
  connect(yaw_, &QSlider::valueChanged, this, gazeMoved);
  connect(pitch_, &QSlider::valueChanged, this, gazeMoved);
  connect(blend_, &QCheckBox::toggled, this, [this] { rebuild(); });
  connect(open, &QPushButton::clicked, this, [this] {
    const QString path = QFileDialog::getOpenFileName(this, tr("Target image"), dialogStart(document_),
                                                      tr("Images (*.png *.jpg *.jpeg *.tif *.tiff *.exr *.hdr *.bmp)"));
    if (!path.isEmpty()) loadTarget(path);
  });
  if (document_) {
    // The compositor depends on the design, not on the eye's gaze (the preview has its own):
    // a gaze drag leaves it alone.
    connect(document_, &SceneDocument::sceneChanged, this, [this] {
      if (!configured_ || !equalButGaze(*configured_, document_->scene())) rebuild();
    });
    connect(document_, &SceneDocument::sceneReplaced, this, [this] { rebuild(); });
  }
  rebuild();
  gazeMoved();
}

PreviewPanel::~PreviewPanel() {
  thread_.quit();
  thread_.wait();
}

std::array<double, 2> PreviewPanel::gaze() const {
  return {yaw_->value() / double(kStepsPerDeg), pitch_->value() / double(kStepsPerDeg)};
}

void PreviewPanel::setGaze(double yaw, double pitch) {
  yaw_->setValue(static_cast<int>(std::lround(yaw * kStepsPerDeg)));
  pitch_->setValue(static_cast<int>(std::lround(pitch * kStepsPerDeg)));
}

void PreviewPanel::rebuild() {
  const Scene scene = document_ ? document_->scene() : Scene{};
  // The gaze may reach the edge of the target (the peripheral FOV).
  const image::DisplayAngles a = image::displayAngles(scene);
  for (int k = 0; k < 2; ++k) {
    QSlider* s = k == 0 ? yaw_ : pitch_;
    const int lim = static_cast<int>(std::floor(a.peripheral_fov_deg[k] / 2 * kStepsPerDeg));
    const QSignalBlocker block(s);
    s->setRange(-lim, lim);
  }
  configured_ = scene;
  const bool blend = blend_->isChecked();
  PreviewWorker* w = worker_;
  QMetaObject::invokeMethod(
      w, [w, scene, blend] { w->configure(scene, blend); }, Qt::QueuedConnection);
  requestRender(false);
  seamTimer_->start();
}

void PreviewPanel::loadTarget(const QString& path) {
  PreviewWorker* w = worker_;
  QMetaObject::invokeMethod(
      w, [w, path] { w->loadTarget(path); }, Qt::QueuedConnection);
  requestRender(false);
  seamTimer_->start();
}

void PreviewPanel::requestRender(bool seam) {
  if (busy_) {
    pending_ = pending_.value_or(false) || seam;
    return;
  }
  busy_ = true;
  PreviewWorker* w = worker_;
  const auto g = gaze();
  const int gen = framesShown_ + 1;
  QMetaObject::invokeMethod(
      w, [w, g, seam, gen] { w->render(g, seam, gen); }, Qt::QueuedConnection);
}

void PreviewPanel::showFrame(const PreviewFrame& f) {
  busy_ = false;
  last_ = f;
  ++framesShown_;
  const std::vector<double> rings{f.ring_deg[0], f.ring_deg[1], f.ring_deg[2]};
  targetView_->setImage(f.target);
  targetView_->setRings(f.target_fov_deg, f.gaze_deg, rings);
  fovealView_->setImage(f.foveal);
  fovealView_->setRings(f.foveal_fov_deg, {0.0, 0.0}, rings);
  peripheralView_->setImage(f.peripheral);
  peripheralView_->setRings(f.target_fov_deg, f.gaze_deg, rings);
  perceivedView_->setImage(f.perceived);
  if (!f.error.isEmpty()) {
    status_->setText(f.error);
  } else {
    QString s = tr("update %1 ms").arg(f.update_ms, 0, 'f', 1);
    if (f.seam_flip) s += tr(" · seam FLIP %1").arg(*f.seam_flip, 0, 'f', 4);
    status_->setText(s);
  }
  emit frameShown();
  if (pending_) {
    const bool seam = *pending_;
    pending_.reset();
    requestRender(seam);
  }
}

}  // namespace fovea::widgets

#include "widgets/preview_panel.h"

#include <QCheckBox>
#include <QComboBox>
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

#include "model/analysis/hoe_travel.h"
#include "model/color/srgb.h"
#include "model/image/foveation.h"
#include "model/image/image_io.h"
#include "model/image/retina_image.h"
#include "model/image/retina_image_figures.h"
#include "model/image/test_target.h"
#include "model/scene/scene_compare.h"
#include "model/vector_state.h"
#include "widgets/dialog_start.h"
#include "widgets/scene_document.h"

namespace fovea::widgets {

namespace {
constexpr int kStepsPerDeg = 4;  // slider resolution: 0.25 deg
constexpr int kViewWidthPx = 640;
constexpr int kAccommodationStepsPerD = 20;  // accommodation slider: 0.05 D
// Retina image mode renders the target at this width (the PSFs and the ray trace cost the same
// at any size; the canvas work scales with the pixels), shown at the view's width.
constexpr int kRetinaWidthPx = 960;

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

// What a Retina image frame is asked for (PreviewPanel::requestRender).
struct RetinaRequest {
  double accommodation_d = 1.25;
  RetinaPreviewOptions options;
};

// Lives on the panel's worker thread; the panel talks to it only through queued calls.
class PreviewWorker : public QObject {
 public:
  explicit PreviewWorker(PreviewPanel* panel) : panel_(panel) {}

  void configure(const Scene& scene, bool blend) {
    clearUpperVectorState();  // queued calls run Qt code on this thread (model/vector_state.h)
    scene_ = scene;
    xp_.reset();
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
    retinaTarget_.release();
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
  // The HOE shift of the retinal image: the studio's one x_p (hoe_travel.h) at this gaze when
  // the scene's HOE follows the gaze (none at zero gaze, as in the live trace), else none.
  std::array<double, 2> hoeShift(std::array<double, 2> gaze) {
    if (!scene_.view.hoe_follows_gaze || (gaze[0] == 0.0 && gaze[1] == 0.0)) return {0, 0};
    if (!xp_ || xp_->first != gaze) xp_.emplace(gaze, hoeTravel(scene_, gaze, sceneXpRule(scene_)).shift_mm);
    return xp_->second;
  }

  // The retinal image at this gaze, accommodation and options (model/image/retina_image.h).
  void renderRetina(PreviewFrame& f, std::array<double, 2> gaze, const RetinaRequest& q, bool blend) {
    f.gaze_deg = gaze;
    f.accommodation_d = q.accommodation_d;
    f.retinaOptions = q.options;
    if (target_.empty()) return;
    if (retinaTarget_.empty()) {
      if (target_.cols == kRetinaWidthPx) {
        retinaTarget_ = target_;
      } else {
        const int h = std::max(1, static_cast<int>(std::lround(target_.rows * double(kRetinaWidthPx) / target_.cols)));
        cv::resize(target_, retinaTarget_, cv::Size(kRetinaWidthPx, h), 0, 0, cv::INTER_AREA);
      }
    }
    image::RetinaImageOptions o;
    o.gaze_deg = gaze;
    o.accommodation_d = q.accommodation_d;
    o.blend = blend;
    o.speckle_patterns = q.options.speckle_patterns;
    o.speckle_grain_pupil = q.options.speckle_grain_pupil;
    o.per_laser_calibration = q.options.per_laser_calibration;
    o.speckle_seed = static_cast<std::uint64_t>(q.options.speckle_seed);
    try {
      const auto t0 = std::chrono::steady_clock::now();
      o.hoe_shift_mm = hoeShift(gaze);
      f.hoe_shift_mm = o.hoe_shift_mm;
      const image::RetinaImageResult r = image::renderRetinaImage(scene_, retinaTarget_, o);
      f.update_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      f.retina = toQImage(r.image, kViewWidthPx);
      QString info;
      if (!r.peripheral.empty() && r.peripheral[r.peripheral_reference].valid) {
        const auto& m = r.peripheral[r.peripheral_reference].metrics;
        info += QString("peripheral spot %1′, MTF50 %2 cpd").arg(m.fwhm_arcmin, 0, 'f', 1).arg(m.mtf50_cpd, 0, 'f', 2);
      }
      if (!r.foveal.empty()) {
        const auto& m = r.foveal[r.foveal_reference].metrics;
        info += QString("%1foveal spot %2′, MTF50 %3 cpd")
                    .arg(info.isEmpty() ? "" : " · ")
                    .arg(m.fwhm_arcmin, 0, 'f', 2)
                    .arg(m.mtf50_cpd, 0, 'f', 1);
      }
      const QString sep = " · ";
      f.speckle_contrast = r.speckle_contrast;
      f.speckle_expected = r.speckle_expected;
      if (r.speckle_contrast) {
        info += (info.isEmpty() ? "" : sep) + QString("speckle contrast %1").arg(*r.speckle_contrast, 0, 'f', 3);
        if (r.speckle_expected) info += QString(" (expected %1)").arg(*r.speckle_expected, 0, 'f', 3);
      }
      f.lateral_colour_arcmin = image::lateralColourShownArcmin(r, o);
      if (f.lateral_colour_arcmin)
        info += (info.isEmpty() ? "" : sep) + QString("lateral colour %1′%2")
                                                  .arg(*f.lateral_colour_arcmin, 0, 'f', 1)
                                                  .arg(o.per_laser_calibration ? " (per-laser calibration)" : "");
      if (o.hoe_shift_mm != std::array<double, 2>{0, 0})
        info += (info.isEmpty() ? "" : sep) +
                QString("HOE x_p %1, %2 mm").arg(o.hoe_shift_mm[0], 0, 'f', 2).arg(o.hoe_shift_mm[1], 0, 'f', 2);
      f.retinaInfo = info;
    } catch (const std::exception& e) {
      f.error = QString::fromStdString(e.what());
    }
  }

  void render(std::array<double, 2> gaze, bool seam, int generation, const std::optional<RetinaRequest>& retina,
              bool blend) {
    clearUpperVectorState();
    PreviewFrame f;
    f.generation = generation;
    f.error = error_;
    error_.clear();
    if (retina) {
      renderRetina(f, gaze, *retina, blend);
    } else if (compositor_) {
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
  cv::Mat target_, retinaTarget_;
  QImage targetImage_;
  QString error_;
  std::unique_ptr<image::FoveatedCompositor> compositor_;
  std::optional<std::pair<std::array<double, 2>, std::array<double, 2>>> xp_;  // gaze -> x_p, this scene
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
  mode_ = new QComboBox(this);
  mode_->setObjectName("PreviewMode");
  mode_->addItem(tr("Displays"));
  mode_->addItem(tr("Retina image"));
  mode_->setToolTip(
      tr("Displays: the two display images and their blend; Retina image: what the retina receives "
         "through both displays and the accommodating eye (issue 29)"));
  status_ = new QLabel(this);
  status_->setObjectName("PreviewStatus");
  top->addWidget(open);
  top->addWidget(mode_);
  top->addWidget(blend_);
  top->addStretch(1);
  layout->addLayout(top);
  // The status on its own line: a narrow dock keeps the top row's buttons whole.
  status_->setWordWrap(true);
  layout->addWidget(status_);

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
  accommodation_ = slider("Accommodation", accommodationLabel_);
  accommodation_->setRange(0, 4 * kAccommodationStepsPerD);
  accommodation_->setValue(static_cast<int>(std::lround(1.25 * kAccommodationStepsPerD)));
  accommodation_->setToolTip(
      tr("The eye's accommodation (diopters): 0.4 D = 2.5 m … 3.3 D = 30 cm; the foveal "
         "image is at 1.25 D (0.8 m) in the prototype"));

  displaysGrid_ = new QWidget(this);
  auto* grid = new QGridLayout(displaysGrid_);
  grid->setContentsMargins(0, 0, 0, 0);
  targetView_ = new PreviewImageView(tr("Target"), this);
  fovealView_ = new PreviewImageView(tr("Foveal (micro-OLED)"), this);
  peripheralView_ = new PreviewImageView(tr("Peripheral (projector)"), this);
  perceivedView_ = new PreviewImageView(tr("Perceived"), this);
  grid->addWidget(targetView_, 0, 0);
  grid->addWidget(fovealView_, 0, 1);
  grid->addWidget(peripheralView_, 1, 0);
  grid->addWidget(perceivedView_, 1, 1);
  layout->addWidget(displaysGrid_);
  retinaView_ = new PreviewImageView(tr("Retina image (visual angle)"), this);
  retinaView_->setObjectName("RetinaImageView");
  retinaControls_ = new RetinaImageControls(this);
  layout->addWidget(retinaControls_);
  retinaInfo_ = new QLabel(this);
  retinaInfo_->setObjectName("RetinaImageInfo");
  retinaInfo_->setWordWrap(true);
  layout->addWidget(retinaView_);
  layout->addWidget(retinaInfo_);
  layout->addStretch(1);

  seamTimer_ = new QTimer(this);
  seamTimer_->setSingleShot(true);
  seamTimer_->setInterval(300);
  connect(seamTimer_, &QTimer::timeout, this, [this] {
    if (mode() == Mode::Displays) requestRender(true);
  });

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
  connect(accommodation_, &QSlider::valueChanged, this, [this] {
    accommodationLabel_->setText(tr("accommodation %1 D").arg(accommodation(), 0, 'f', 2));
    if (mode() == Mode::RetinaImage) requestRender(false);
  });
  connect(retinaControls_, &RetinaImageControls::changed, this, [this] {
    if (mode() == Mode::RetinaImage) requestRender(false);
  });
  connect(mode_, &QComboBox::currentIndexChanged, this, [this] {
    applyMode();
    requestRender(false);
  });
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
  accommodationLabel_->setText(tr("accommodation %1 D").arg(accommodation(), 0, 'f', 2));
  applyMode();
  rebuild();
  gazeMoved();
}

PreviewPanel::Mode PreviewPanel::mode() const {
  return mode_->currentIndex() == 1 ? Mode::RetinaImage : Mode::Displays;
}

void PreviewPanel::setMode(Mode m) {
  mode_->setCurrentIndex(m == Mode::RetinaImage ? 1 : 0);
}

double PreviewPanel::accommodation() const {
  return accommodation_->value() / double(kAccommodationStepsPerD);
}

void PreviewPanel::setAccommodation(double d) {
  accommodation_->setValue(static_cast<int>(std::lround(d * kAccommodationStepsPerD)));
}

RetinaPreviewOptions PreviewPanel::retinaOptions() const {
  return retinaControls_->options();
}

void PreviewPanel::setRetinaOptions(const RetinaPreviewOptions& o) {
  retinaControls_->setOptions(o);
}

void PreviewPanel::applyMode() {
  const bool retina = mode() == Mode::RetinaImage;
  displaysGrid_->setVisible(!retina);
  retinaView_->setVisible(retina);
  retinaInfo_->setVisible(retina);
  retinaControls_->setVisible(retina);
  status_->setVisible(!retina);  // in Retina image mode: errors only (showFrame)
  accommodation_->setVisible(retina);
  accommodationLabel_->setVisible(retina);
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
  std::optional<RetinaRequest> retina;
  if (mode() == Mode::RetinaImage) retina = RetinaRequest{accommodation(), retinaOptions()};
  const bool blend = blend_->isChecked();
  QMetaObject::invokeMethod(
      w, [w, g, seam, gen, retina, blend] { w->render(g, seam && !retina, gen, retina, blend); }, Qt::QueuedConnection);
}

void PreviewPanel::showFrame(const PreviewFrame& f) {
  busy_ = false;
  last_ = f;
  ++framesShown_;
  if (f.accommodation_d) {  // a Retina image frame
    retinaView_->setImage(f.retina);
    // The render time ends the info line; the status line (a row above the image, which a
    // 1366 x 768 screen cannot spare) shows only an error in this mode.
    retinaInfo_->setText(
        f.error.isEmpty()
            ? f.retinaInfo +
                  tr(" · rendered in %1 ms at %2 D").arg(f.update_ms, 0, 'f', 0).arg(*f.accommodation_d, 0, 'f', 2)
            : f.retinaInfo);
    status_->setText(f.error);
    status_->setVisible(mode() == Mode::Displays || !f.error.isEmpty());
    emit frameShown();
    if (pending_) {
      const bool seam = *pending_;
      pending_.reset();
      requestRender(seam);
    }
    return;
  }
  const std::vector<double> rings{f.ring_deg[0], f.ring_deg[1], f.ring_deg[2]};
  targetView_->setImage(f.target);
  targetView_->setRings(f.target_fov_deg, f.gaze_deg, rings);
  fovealView_->setImage(f.foveal);
  fovealView_->setRings(f.foveal_fov_deg, {0.0, 0.0}, rings);
  peripheralView_->setImage(f.peripheral);
  peripheralView_->setRings(f.target_fov_deg, f.gaze_deg, rings);
  perceivedView_->setImage(f.perceived);
  status_->setVisible(mode() == Mode::Displays || !f.error.isEmpty());
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

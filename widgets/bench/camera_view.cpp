#include "widgets/bench/camera_view.h"

#include <QPainter>

namespace fovea::widgets {

CameraView::CameraView(QWidget* parent) : QWidget(parent) {
  setObjectName("CameraView");
  setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Expanding);
  setAttribute(Qt::WA_OpaquePaintEvent);
}

void CameraView::setFrame(const QImage& image, const QString& caption) {
  image_ = image;
  caption_ = caption;
  update();
}

void CameraView::setCrosshair(bool on) {
  crosshair_ = on;
  update();
}

void CameraView::setBanner(const QString& text) {
  banner_ = text;
  update();
}

void CameraView::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.fillRect(rect(), QColor(20, 20, 24));
  QRectF target;
  if (!image_.isNull()) {
    const QSizeF s = QSizeF(image_.size()).scaled(size(), Qt::KeepAspectRatio);
    target = QRectF(QPointF((width() - s.width()) / 2, (height() - s.height()) / 2), s);
    p.setRenderHint(QPainter::SmoothPixmapTransform);
    p.drawImage(target, image_);
  } else {
    target = rect();
    p.setPen(QColor(160, 160, 160));
    p.drawText(rect(), Qt::AlignCenter, tr("no camera frame"));
  }
  if (crosshair_ && !image_.isNull()) {
    // The optical centre of a W x H sensor is at ((W-1)/2, (H-1)/2).
    const double cx = target.left() + (0.5 * (image_.width() - 1) + 0.5) * target.width() / image_.width();
    const double cy = target.top() + (0.5 * (image_.height() - 1) + 0.5) * target.height() / image_.height();
    p.setPen(QPen(QColor(255, 60, 60), 1));
    p.drawLine(QPointF(target.left(), cy), QPointF(cx - 6, cy));
    p.drawLine(QPointF(cx + 6, cy), QPointF(target.right(), cy));
    p.drawLine(QPointF(cx, target.top()), QPointF(cx, cy - 6));
    p.drawLine(QPointF(cx, cy + 6), QPointF(cx, target.bottom()));
    p.drawEllipse(QPointF(cx, cy), 12, 12);
  }
  QFont f = font();
  if (!caption_.isEmpty()) {
    p.setFont(f);
    const QRect r = p.fontMetrics().boundingRect(caption_).adjusted(-4, -2, 4, 2);
    const QRect box(4, height() - r.height() - 4, r.width(), r.height());
    p.fillRect(box, QColor(0, 0, 0, 160));
    p.setPen(Qt::white);
    p.drawText(box, Qt::AlignCenter, caption_);
  }
  if (!banner_.isEmpty()) {
    f.setBold(true);
    p.setFont(f);
    const QRect r = p.fontMetrics().boundingRect(banner_).adjusted(-6, -3, 6, 3);
    const QRect box(4, 4, r.width(), r.height());
    p.fillRect(box, QColor(230, 140, 0));
    p.setPen(Qt::black);
    p.drawText(box, Qt::AlignCenter, banner_);
  }
}

}  // namespace fovea::widgets

#include "app/studio/window_capture.h"

#include <QOpenGLWidget>
#include <QPainter>
#include <QRegularExpression>
#include <QSize>
#include <QWidget>

namespace fovea::studio {

QImage captureWithOpenGl(QWidget* window) {
  QImage image = window->grab().toImage().convertToFormat(QImage::Format_RGB32);
  QPainter painter(&image);
  const double dpr = image.devicePixelRatio();
  for (QOpenGLWidget* gl : window->findChildren<QOpenGLWidget*>()) {
    if (!gl->isVisible()) continue;
    // Opaque, as the screen shows it: the framebuffer's alpha (text and translucent passes
    // leave it below 1) must neither let the widget grab underneath show through nor lighten
    // the colours.
    const QImage content = opaqueFramebuffer(gl->grabFramebuffer());
    if (content.isNull()) continue;
    const QRect target(gl->mapTo(window, QPoint(0, 0)), gl->size());
    painter.drawImage(QRectF(target.topLeft() * 1.0, QSizeF(target.size()) * 1.0), content,
                      QRectF(0, 0, content.width(), content.height()));
  }
  Q_UNUSED(dpr);
  return image;
}

QImage opaqueFramebuffer(const QImage& grab) {
  if (grab.isNull() || !grab.hasAlphaChannel()) return grab.convertToFormat(QImage::Format_RGB32);
  // Same channel values in ARGB order (a premultiplied grab stays premultiplied: no division).
  QImage argb = grab.convertToFormat(grab.pixelFormat().premultiplied() == QPixelFormat::Premultiplied
                                         ? QImage::Format_ARGB32_Premultiplied
                                         : QImage::Format_ARGB32);
  for (int y = 0; y < argb.height(); ++y) {
    auto* line = reinterpret_cast<QRgb*>(argb.scanLine(y));
    for (int x = 0; x < argb.width(); ++x) line[x] |= 0xff000000u;
  }
  return argb.convertToFormat(QImage::Format_RGB32);
}

bool parseWindowSize(const QString& text, QSize* size) {
  static const QRegularExpression re("^(\\d{2,5})x(\\d{2,5})$");
  const auto m = re.match(text.trimmed());
  if (!m.hasMatch()) return false;
  const int w = m.captured(1).toInt(), h = m.captured(2).toInt();
  if (w < 64 || h < 64 || w > 8192 || h > 8192) return false;
  *size = QSize(w, h);
  return true;
}

}  // namespace fovea::studio

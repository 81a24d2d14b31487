#include "widgets/binocular_top_view.h"

#include <QPainter>
#include <QPainterPath>

#include <algorithm>
#include <cmath>

#include "model/scene/scene_geometry.h"

namespace fovea::widgets {

namespace {
// The line of sight's direction (model/scene/scene_geometry.h) projected on the top view's
// plane (x, z).
QPointF topDirection(const std::array<double, 2>& g) {
  const Eigen::Vector3d d = gazeDirection(g[0], g[1]);
  const double n = std::hypot(d.x(), d.z());
  return n > 0 ? QPointF(d.x() / n, d.z() / n) : QPointF(0, 1);
}
// A round number of millimetres close to `span` / 4 (1, 2, 5 steps).
double niceStep(double span) {
  const double raw = span / 4, p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * p >= raw) return m * p;
  return 10 * p;
}
QString mmText(double mm) {
  return mm >= 1000 ? QString::number(mm / 1000, 'g', 3) + " m"
         : mm >= 10 ? QString::number(mm / 10, 'g', 3) + " cm"
                    : QString::number(mm, 'g', 3) + " mm";
}
}  // namespace

BinocularTopView::BinocularTopView(QWidget* parent) : QWidget(parent) {
  setObjectName("binocularTopView");
  setToolTip(
      tr("Seen from above: the eyes' rotation centres, their lines of sight and the fixation point. "
         "Lateral and depth scales differ."));
  setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Expanding);
}

void BinocularTopView::setState(const State& s) {
  state_ = s;
  update();
}

QPointF BinocularTopView::Mapping::map(double x_mm, double z_mm) const {
  return {plot.center().x() + x_mm / x_half_mm * plot.width() / 2, plot.bottom() - z_mm / z_max_mm * plot.height()};
}

BinocularTopView::Mapping BinocularTopView::mapping() const {
  const QFontMetricsF fm(font());
  Mapping m;
  // Margins: the depth scale on the left, the eyes' labels and lateral scale below, the
  // distance label above.
  m.plot = QRectF(rect()).adjusted(fm.horizontalAdvance("2.5 m") + 10, fm.height() + 8, -12, -(2 * fm.height() + 14));
  const double fix_z = state_.fixation_mm ? state_.fixation_mm->z() : 0;
  const double fix_x = state_.fixation_mm ? std::abs(state_.fixation_mm->x()) : 0;
  m.z_max_mm = std::max(300.0, fix_z * 1.12);
  m.x_half_mm = std::max(state_.ipd_mm * 1.3, fix_x * 1.15 + 10);
  return m;
}

std::optional<QPointF> BinocularTopView::fixationPixel() const {
  if (!state_.binocular || !state_.fixation_mm) return std::nullopt;
  return mapping().map(state_.fixation_mm->x(), state_.fixation_mm->z());
}

void BinocularTopView::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.setRenderHint(QPainter::Antialiasing);
  const QPalette pal = palette();
  p.fillRect(rect(), pal.base());
  if (!state_.binocular) {
    p.setPen(pal.text().color());
    p.drawText(rect().adjusted(8, 8, -8, -8), Qt::AlignCenter | Qt::TextWordWrap,
               tr("A monocular scene: one eye, no vergence. A binocular scene (for example "
                  "scenes/binocular-prototype.json) shows both eyes and their fixation point here."));
    return;
  }
  const Mapping m = mapping();
  const QFontMetricsF fm(font());
  // Frame and depth scale.
  p.setPen(QPen(pal.mid().color(), 1));
  p.drawRect(m.plot);
  const double zs = niceStep(m.z_max_mm);
  p.setPen(pal.text().color());
  for (double z = 0; z <= m.z_max_mm + 1e-9; z += zs) {
    const QPointF a = m.map(-m.x_half_mm, z);
    p.setPen(QPen(pal.mid().color(), 1, Qt::DotLine));
    p.drawLine(a, m.map(m.x_half_mm, z));
    p.setPen(pal.text().color());
    const QString t = mmText(z);
    p.drawText(QRectF(0, a.y() - fm.height() / 2, m.plot.left() - 4, fm.height()), Qt::AlignRight | Qt::AlignVCenter,
               t);
  }
  const double half = state_.ipd_mm / 2;
  const QPointF cl = m.map(-half, 0), cr = m.map(half, 0);
  // Lines of sight: to the fixation point, or to the plot's edge when they do not meet.
  auto rayEnd = [&](const std::array<double, 2>& g, double cx) {
    if (state_.fixation_mm) return m.map(state_.fixation_mm->x(), state_.fixation_mm->z());
    const QPointF d = topDirection(g);
    const double t = d.y() > 1e-9 ? m.z_max_mm / d.y() : 2 * m.x_half_mm;
    return m.map(cx + d.x() * t, d.y() * t);
  };
  const QColor leftColour(0x2b, 0x7b, 0xd8), rightColour(0xd8, 0x5b, 0x2b);
  p.setClipRect(m.plot.adjusted(-6, -6, 6, 6));
  p.setPen(QPen(leftColour, 2));
  p.drawLine(cl, rayEnd(state_.left_deg, -half));
  p.setPen(QPen(rightColour, 2));
  p.drawLine(cr, rayEnd(state_.right_deg, half));
  // Eyes: rotation centres.
  for (const auto& [c, col] : {std::pair{cl, leftColour}, std::pair{cr, rightColour}}) {
    p.setPen(QPen(pal.text().color(), 1));
    p.setBrush(col);
    p.drawEllipse(c, 5, 5);
  }
  if (auto f = fixationPixel()) {
    p.setPen(QPen(pal.text().color(), 1.5));
    p.setBrush(Qt::NoBrush);
    p.drawEllipse(*f, 5, 5);
    p.drawLine(*f + QPointF(-8, 0), *f + QPointF(8, 0));
    p.drawLine(*f + QPointF(0, -8), *f + QPointF(0, 8));
  }
  p.setClipping(false);
  // Labels: eyes and IPD below, the lateral scale, the fixation distance above.
  p.setPen(pal.text().color());
  const double below = m.plot.bottom() + 4;
  p.drawText(QRectF(cl.x() - 40, below, 38, fm.height()), Qt::AlignRight, tr("L"));
  p.drawText(QRectF(cr.x() + 2, below, 38, fm.height()), Qt::AlignLeft, tr("R"));
  const QString scales =
      tr("IPD %1 mm · x ±%2 · z to %3").arg(state_.ipd_mm, 0, 'f', 1).arg(mmText(m.x_half_mm), mmText(m.z_max_mm));
  p.drawText(QRectF(2, below + fm.height() + 2, width() - 4, fm.height()), Qt::AlignHCenter,
             fm.elidedText(scales, Qt::ElideRight, width() - 4));
  const QString top =
      state_.fixation_mm
          ? tr("fixation %1 · vergence %2°").arg(mmText(state_.fixation_mm->norm())).arg(state_.vergence_deg, 0, 'f', 2)
          : tr("lines of sight do not meet (no fixation)");
  p.drawText(QRectF(0, 2, width(), fm.height()), Qt::AlignHCenter, fm.elidedText(top, Qt::ElideRight, width() - 4));
}

}  // namespace fovea::widgets

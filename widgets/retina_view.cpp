#include "widgets/retina_view.h"

#include <QFontMetricsF>
#include <QPainter>
#include <QPainterPath>
#include <QStringList>

#include <algorithm>
#include <cmath>

#include "viz/efficiency_colors.h"
#include "viz/scene_actors.h"

namespace fovea::widgets {

namespace {
QColor toQColor(const std::array<double, 3>& c, double alpha = 1.0) {
  return QColor::fromRgbF(static_cast<float>(c[0]), static_cast<float>(c[1]), static_cast<float>(c[2]),
                          static_cast<float>(alpha));
}
bool hiddenIn(const std::vector<double>& hidden, double nm) {
  return std::any_of(hidden.begin(), hidden.end(), [nm](double h) { return std::abs(h - nm) < 1e-6; });
}
}  // namespace

RetinaView::RetinaView(QWidget* parent) : QWidget(parent) {
  setMinimumSize(240, 200);
  setAttribute(Qt::WA_OpaquePaintEvent);
}

void RetinaView::setResult(std::shared_ptr<const LiveTraceResult> result, const std::vector<double>& hidden) {
  result_ = std::move(result);
  hidden_ = hidden;
  box_ = {};
  if (result_) {
    for (const TracedRay& r : result_->trace.ray_list) {
      if (!r.in_pupil || !(r.efficiency >= viz::kLowEfficiency) || hiddenIn(hidden_, r.wavelength_nm)) continue;
      if (!box_.valid) {
        box_ = {true, r.field_deg[0], r.field_deg[0], r.field_deg[1], r.field_deg[1]};
        continue;
      }
      box_.yaw_min = std::min(box_.yaw_min, r.field_deg[0]);
      box_.yaw_max = std::max(box_.yaw_max, r.field_deg[0]);
      box_.pitch_min = std::min(box_.pitch_min, r.field_deg[1]);
      box_.pitch_max = std::max(box_.pitch_max, r.field_deg[1]);
    }
  }
  update();
}

QImage RetinaView::render(const QSize& size) {
  QImage image(size, QImage::Format_RGB32);
  QPainter p(&image);
  paint(p, QRect(QPoint(0, 0), size));
  return image;
}

void RetinaView::paintEvent(QPaintEvent*) {
  QPainter p(this);
  paint(p, rect());
}

void RetinaView::paint(QPainter& p, const QRect& area) {
  p.setRenderHint(QPainter::Antialiasing, true);
  p.fillRect(area, QColor(22, 24, 30));
  QFont small = p.font();
  small.setPixelSize(11);
  p.setFont(small);
  // Angular frame: +-60 deg yaw, +-50 deg pitch (the HOE spans ~90 x 79 deg), widened to
  // keep every drawn ray in view; square degrees.
  double yaw_half = 60, pitch_half = 50;
  if (result_)
    for (const TracedRay& r : result_->trace.ray_list)
      if (r.in_pupil) {
        yaw_half = std::max(yaw_half, std::ceil(std::abs(r.field_deg[0]) / 10.0) * 10.0);
        pitch_half = std::max(pitch_half, std::ceil(std::abs(r.field_deg[1]) / 10.0) * 10.0);
      }
  // The numbers above the plot, as pieces wrapped to the width (a narrow dock gets more
  // lines, never a clipped number).
  QFont bold = small;
  bold.setBold(true);
  const QString head = tr("Retina: field seen through the pupil");
  QStringList pieces;
  if (!result_) {
    pieces << tr("tracing…");
  } else if (!result_->error.empty()) {
    pieces << tr("trace failed: %1").arg(QString::fromStdString(result_->error));
  } else {
    const TraceResult& t = result_->trace;
    pieces << QString::fromUtf8("gaze %1°, %2°").arg(t.gaze_deg[0], 0, 'f', 1).arg(t.gaze_deg[1], 0, 'f', 1)
           // The exact FOV (trace_fov.h), named: ours (arrival directions), as the Gaze dock.
           << QString::fromUtf8("FOV %1° × %2° (diagonal %3°), ours, exact")
                  .arg(result_->fov.horizontal, 0, 'f', 2)
                  .arg(result_->fov.vertical, 0, 'f', 2)
                  .arg(result_->fov.diagonal, 0, 'f', 2)
           << QString::fromUtf8("mean η %1").arg(t.mean_efficiency, 0, 'f', 2)
           << tr("%1 rays in the pupil").arg(t.rays_in_pupil);
    if (result_->hoe_shift_mm[0] != 0.0 || result_->hoe_shift_mm[1] != 0.0)
      pieces << QString::fromUtf8("HOE x_p %1, %2 mm")
                    .arg(result_->hoe_shift_mm[0], 0, 'f', 2)
                    .arg(result_->hoe_shift_mm[1], 0, 'f', 2);
  }
  QStringList lines;
  {
    const QFontMetricsF fm(small);
    const double room = area.width() - 16.0;
    for (const QString& piece : pieces) {
      if (!lines.isEmpty() && fm.horizontalAdvance(lines.back() + "   " + piece) <= room)
        lines.back() += "   " + piece;
      else
        lines << piece;
    }
  }
  const double headerBottom = 20.0 + 15.0 * lines.size() + 8.0;
  const QRectF plot = QRectF(area).adjusted(44, std::max(58.0, headerBottom), -58, -30);
  const double scale = std::min(plot.width() / (2 * yaw_half), plot.height() / (2 * pitch_half));
  const QPointF centre = plot.center();
  auto at = [&](double yaw, double pitch) { return QPointF(centre.x() + yaw * scale, centre.y() - pitch * scale); };
  const QRectF frame(at(-yaw_half, pitch_half), at(yaw_half, -pitch_half));
  p.fillRect(frame, QColor(8, 8, 10));
  // Grid every 10 deg with labels every 30.
  p.setPen(QPen(QColor(60, 64, 74), 1));
  for (int d = -static_cast<int>(yaw_half); d <= yaw_half; d += 10) p.drawLine(at(d, -pitch_half), at(d, pitch_half));
  for (int d = -static_cast<int>(pitch_half); d <= pitch_half; d += 10) p.drawLine(at(-yaw_half, d), at(yaw_half, d));
  p.setPen(QColor(170, 174, 184));
  for (int d = -static_cast<int>(yaw_half) / 30 * 30; d <= yaw_half; d += 30)
    p.drawText(QRectF(at(d, -pitch_half) + QPointF(-20, 3), QSizeF(40, 14)), Qt::AlignCenter, QString::number(d));
  for (int d = -static_cast<int>(pitch_half) / 30 * 30; d <= pitch_half; d += 30)
    p.drawText(QRectF(at(-yaw_half, d) + QPointF(-40, -7), QSizeF(36, 14)), Qt::AlignRight | Qt::AlignVCenter,
               QString::number(d));
  p.drawText(QRectF(frame.left(), frame.bottom() + 14, frame.width(), 14), Qt::AlignCenter, tr("yaw (deg)"));
  // The pitch axis's title, upwards along the left edge: its 14 px line spans frame.left - 40
  // .. - 26, clear of the right-aligned tick numbers (frame.left - 4 back to ~ - 22) and inside
  // the 44 px margin (it started 4 px left of the dock at - 48 .. - 34: clipped at 1920x1080).
  p.save();
  p.translate(frame.left() - 26, frame.center().y());
  p.rotate(-90);
  p.drawText(QRectF(-60, -14, 120, 14), Qt::AlignCenter, tr("pitch (deg)"));
  p.restore();

  cells_ = 0;
  if (result_ && result_->grid[0] > 1 && result_->grid[1] > 1) {
    const int nx = result_->grid[0], ny = result_->grid[1];
    const std::size_t per = static_cast<std::size_t>(nx) * ny;
    const auto& rays = result_->trace.ray_list;
    const std::size_t blocks = per ? rays.size() / per : 0;
    int shown = 0;
    for (std::size_t b = 0; b < blocks; ++b)
      if (!hiddenIn(hidden_, rays[b * per].wavelength_nm)) ++shown;
    const double alpha = shown > 1 ? 1.0 / std::sqrt(static_cast<double>(shown)) : 1.0;
    p.setPen(Qt::NoPen);
    for (std::size_t b = 0; b < blocks; ++b) {
      if (hiddenIn(hidden_, rays[b * per].wavelength_nm)) continue;
      for (int y = 0; y + 1 < ny; ++y)
        for (int x = 0; x + 1 < nx; ++x) {
          const TracedRay* c[4] = {&rays[b * per + y * nx + x], &rays[b * per + y * nx + x + 1],
                                   &rays[b * per + (y + 1) * nx + x + 1], &rays[b * per + (y + 1) * nx + x]};
          if (!(c[0]->in_pupil && c[1]->in_pupil && c[2]->in_pupil && c[3]->in_pupil)) continue;
          double eta = 0;
          QPolygonF quad;
          for (const TracedRay* r : c) {
            eta += r->efficiency / 4;
            quad << at(r->field_deg[0], r->field_deg[1]);
          }
          p.setBrush(toQColor(viz::efficiencyColor(eta), alpha));
          p.drawPolygon(quad);
          ++cells_;
        }
    }
  }
  // Fovea and gaze.
  if (result_) {
    const double f = result_->scene.eye.fovea_radius_deg;
    p.setBrush(Qt::NoBrush);
    p.setPen(QPen(QColor(255, 140, 26), 2));
    p.drawEllipse(at(0, 0), f * scale, f * scale);
  }
  p.setPen(QPen(QColor(230, 230, 230), 1));
  p.drawLine(at(-2, 0), at(2, 0));
  p.drawLine(at(0, -2), at(0, 2));
  // The box of the drawn rays and its size, named as such: the extent of the ray grid's lit
  // cells (about a ray spacing inside the exact FOV the header gives; issue 26, one number per
  // quantity: the two definitions are told apart).
  if (box_.valid) {
    const QRectF b(at(box_.yaw_min, box_.pitch_max), at(box_.yaw_max, box_.pitch_min));
    p.setPen(QPen(QColor(255, 255, 255), 1.5, Qt::DashLine));
    p.setBrush(Qt::NoBrush);
    p.drawRect(b);
    p.setPen(Qt::white);
    p.drawText(QRectF(b.left() - 40, b.top() - 15, b.width() + 80, 14), Qt::AlignCenter,
               tr("%1° drawn rays").arg(box_.yaw_max - box_.yaw_min, 0, 'f', 1));
    p.save();
    p.translate(b.right() + 4, b.center().y());
    p.rotate(90);
    p.drawText(QRectF(-60, -14, 120, 14), Qt::AlignCenter,
               tr("%1° drawn rays").arg(box_.pitch_max - box_.pitch_min, 0, 'f', 1));
    p.restore();
  }
  // The numbers, wrapped to the width (computed first: the plot starts below them).
  p.setFont(bold);
  p.setPen(QColor(235, 235, 235));
  p.drawText(QRectF(area.left() + 8, area.top() + 4, area.width() - 16, 16), Qt::AlignLeft | Qt::AlignVCenter, head);
  p.setFont(small);
  for (int i = 0; i < lines.size(); ++i)
    p.drawText(QRectF(area.left() + 8, area.top() + 20 + 15 * i, area.width() - 16, 16),
               Qt::AlignLeft | Qt::AlignVCenter, lines[i]);
  // Colour scale at the right.
  // 12 px bar, labels to its right up to 2 px from the edge ("< 0.1" is ~27 px at 11 px).
  const QRectF bar(area.right() - 46, plot.top() + 22, 12, plot.height() * 0.55);
  for (int i = 0; i < 64; ++i) {
    const double e = viz::kLowEfficiency + (1 - viz::kLowEfficiency) * (i + 0.5) / 64;
    p.fillRect(QRectF(bar.left(), bar.bottom() - bar.height() * (i + 1) / 64, bar.width(), bar.height() / 64 + 0.5),
               toQColor(viz::efficiencyColor(e)));
  }
  p.fillRect(QRectF(bar.left(), bar.bottom() + 4, bar.width(), 10), toQColor(viz::kLowEfficiencyGray));
  p.setPen(QColor(200, 200, 200));
  p.drawText(QRectF(bar.left() - 6, bar.top() - 16, 30, 14), Qt::AlignCenter, "η");
  p.drawText(QRectF(bar.right() + 2, bar.top() - 6, 30, 12), Qt::AlignLeft | Qt::AlignVCenter, "1");
  p.drawText(QRectF(bar.right() + 2, bar.bottom() - 6, 30, 12), Qt::AlignLeft | Qt::AlignVCenter, "0.1");
  p.drawText(QRectF(bar.right() + 2, bar.bottom() + 3, 32, 12), Qt::AlignLeft | Qt::AlignVCenter, "< 0.1");
}

}  // namespace fovea::widgets

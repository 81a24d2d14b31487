#include "widgets/plots/plot_render.h"

#include <QBuffer>
#include <QCategoryAxis>
#include <QChart>
#include <QChartView>
#include <QCoreApplication>
#include <QFileInfo>
#include <QLegendMarker>
#include <QLineSeries>
#include <QLogValueAxis>
#include <QPainter>
#include <QSaveFile>
#include <QScatterSeries>
#include <QSvgGenerator>
#include <QValueAxis>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

namespace fovea::widgets {

namespace {

struct Range {
  double lo = std::numeric_limits<double>::infinity(), hi = -std::numeric_limits<double>::infinity();
  void add(double v, bool positiveOnly) {
    if (!std::isfinite(v) || (positiveOnly && v <= 0)) return;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  bool valid() const { return lo <= hi; }
};

QAbstractAxis* makeAxis(const PlotAxis& a, Range data, QFont font) {
  if (!a.categories.isEmpty()) {  // labels at the values 0, 1, ... (a bar chart's names)
    auto* axis = new QCategoryAxis;
    for (int i = 0; i < a.categories.size(); ++i) axis->append(a.categories[i], i);
    axis->setLabelsPosition(QCategoryAxis::AxisLabelsPositionOnValue);
    if (a.labelAngle != 0) axis->setLabelsAngle(a.labelAngle);
    axis->setRange(-0.6, a.categories.size() - 0.4);
    axis->setGridLineVisible(false);
    axis->setTitleText(a.title);
    axis->setTitleFont(font);
    return axis;
  }
  if (a.min) data.lo = *a.min;
  if (a.max) data.hi = *a.max;
  if (!data.valid()) data = {0.0, 1.0};
  if (a.log) {
    auto* axis = new QLogValueAxis;
    axis->setBase(10.0);
    axis->setLabelFormat("%.0e");
    const double lo = std::pow(10.0, std::floor(std::log10(std::max(data.lo, 1e-300))));
    const double hi = std::pow(10.0, std::ceil(std::log10(std::max(data.hi, lo * 10))));
    axis->setRange(lo, hi);
    axis->setMinorTickCount(-1);
    axis->setTitleText(a.title);
    axis->setTitleFont(font);
    return axis;
  }
  auto* axis = new QValueAxis;
  double lo = data.lo, hi = data.hi;
  if (hi - lo < 1e-12) lo -= 0.5, hi += 0.5;
  const double pad = 0.04 * (hi - lo);
  axis->setRange(a.min ? lo : lo - pad, a.max ? hi : hi + pad);
  if (!(a.min && a.max)) {
    axis->applyNiceNumbers();
    if (a.min && axis->min() < *a.min) axis->setMin(*a.min);
  }
  axis->setLabelFormat("%.4g");
  axis->setTitleText(a.title);
  axis->setTitleFont(font);
  return axis;
}

}  // namespace

QChart* buildChart(const PlotData& plot, bool dark) {
  auto* chart = new QChart;
  chart->setTheme(dark ? QChart::ChartThemeDark : QChart::ChartThemeLight);
  chart->setTitle(plot.title);
  QFont titleFont = chart->titleFont();
  titleFont.setPointSizeF(titleFont.pointSizeF() * 1.25);
  titleFont.setBold(true);
  chart->setTitleFont(titleFont);
  chart->legend()->setAlignment(Qt::AlignBottom);
  chart->setAnimationOptions(QChart::NoAnimation);
  QFont axisFont;
  axisFont.setPointSizeF(axisFont.pointSizeF() * 1.05);

  Range xr, yr, y2r;
  for (const PlotSeries& s : plot.series)
    for (const QPointF& p : s.points) {
      xr.add(p.x(), plot.x.log);
      (s.rightAxis ? y2r : yr).add(p.y(), s.rightAxis ? plot.y2.log : plot.y.log);
    }
  QAbstractAxis* ax = makeAxis(plot.x, xr, axisFont);
  QAbstractAxis* ay = makeAxis(plot.y, yr, axisFont);
  chart->addAxis(ax, Qt::AlignBottom);
  chart->addAxis(ay, Qt::AlignLeft);
  QAbstractAxis* ay2 = nullptr;
  if (plot.hasY2) {
    ay2 = makeAxis(plot.y2, y2r, axisFont);
    chart->addAxis(ay2, Qt::AlignRight);
  }

  for (const PlotSeries& s : plot.series) {
    if (s.style == PlotSeries::Style::Segments) {  // one line series per pair, one legend entry
      for (qsizetype i = 0; i + 1 < s.points.size(); i += 2) {
        auto* seg = new QLineSeries;
        seg->setName(s.name);
        seg->append(s.points[i]);
        seg->append(s.points[i + 1]);
        chart->addSeries(seg);
        QPen pen = seg->pen();
        pen.setWidthF(s.lineWidth);
        pen.setCapStyle(Qt::FlatCap);
        if (s.color.isValid()) pen.setColor(s.color);
        seg->setPen(pen);
        seg->attachAxis(ax);
        seg->attachAxis(s.rightAxis && ay2 ? ay2 : ay);
        if (i > 0)
          for (QLegendMarker* m : chart->legend()->markers(seg)) m->setVisible(false);
      }
      continue;
    }
    QXYSeries* xy = nullptr;
    if (s.style == PlotSeries::Style::Scatter) {
      auto* sc = new QScatterSeries;
      sc->setMarkerSize(s.markerSize);
      sc->setBorderColor(Qt::transparent);
      xy = sc;
    } else {
      xy = new QLineSeries;
    }
    xy->setName(s.name);
    xy->append(s.points);
    chart->addSeries(xy);
    if (s.color.isValid()) xy->setColor(s.color);
    if (s.style != PlotSeries::Style::Scatter) {
      QPen pen = xy->pen();
      pen.setWidthF(s.name == "perceived" ? 3.0 : s.lineWidth);
      if (s.color.isValid()) pen.setColor(s.color);
      if (s.style == PlotSeries::Style::Dashed) pen.setStyle(Qt::DashLine);
      xy->setPen(pen);
    }
    xy->attachAxis(ax);
    xy->attachAxis(s.rightAxis && ay2 ? ay2 : ay);
  }
  if (plot.series.isEmpty()) chart->legend()->hide();
  return chart;
}

namespace {

// A chart view laid out at `size` without appearing on screen: the chart only takes the
// view's size when the view gets its resize event, i.e. when it is (invisibly) shown.
void layOut(QChartView& view, QSize size) {
  view.setRenderHint(QPainter::Antialiasing);
  view.setFrameShape(QFrame::NoFrame);
  view.setAttribute(Qt::WA_DontShowOnScreen);
  view.resize(size);
  view.show();
  view.chart()->resize(QSizeF(size));
  QCoreApplication::sendPostedEvents();
}

}  // namespace

QImage renderPlotImage(const PlotData& plot, QSize size, double scale) {
  QChartView view(buildChart(plot));
  layOut(view, size);
  QImage image(size * scale, QImage::Format_RGB32);
  image.fill(Qt::white);
  QPainter painter(&image);
  painter.setRenderHint(QPainter::Antialiasing);
  view.render(&painter, QRectF(QPointF(0, 0), QSizeF(size) * scale), view.rect());
  return image;
}

bool exportPlot(const PlotData& plot, const QString& path, QString* error, QSize size) {
  auto fail = [&](const QString& m) {
    if (error) *error = m;
    return false;
  };
  const QString ext = QFileInfo(path).suffix().toLower();
  QByteArray bytes;
  if (ext == "csv") {
    bytes = plotCsv(plot).toUtf8();
  } else if (ext == "png") {
    QBuffer buffer(&bytes);
    buffer.open(QIODevice::WriteOnly);
    if (!renderPlotImage(plot, size).save(&buffer, "PNG")) return fail(QStringLiteral("could not encode the PNG"));
  } else if (ext == "svg") {
    QBuffer buffer(&bytes);
    buffer.open(QIODevice::WriteOnly);
    QSvgGenerator svg;
    svg.setOutputDevice(&buffer);
    svg.setSize(size);
    svg.setViewBox(QRect(QPoint(0, 0), size));
    svg.setTitle(plot.title);
    svg.setDescription(plot.caption);
    QChartView view(buildChart(plot));
    layOut(view, size);
    QPainter painter;
    if (!painter.begin(&svg)) return fail(QStringLiteral("could not start the SVG"));
    painter.fillRect(QRect(QPoint(0, 0), size), Qt::white);
    view.render(&painter, QRectF(QPointF(0, 0), QSizeF(size)), view.rect());
    painter.end();
  } else {
    return fail(QStringLiteral("unknown export format \"%1\": use .png, .svg or .csv").arg(ext));
  }
  QSaveFile out(path);
  if (!out.open(QIODevice::WriteOnly)) return fail(out.errorString());
  if (out.write(bytes) != bytes.size()) {
    out.cancelWriting();
    return fail(out.errorString());
  }
  if (!out.commit()) return fail(out.errorString());
  return true;
}

}  // namespace fovea::widgets

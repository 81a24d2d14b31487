#pragma once
// A plot as data: what is drawn (series over axes) and the table behind it (exported as
// CSV, with units in the column headers). Built from analysis results by plot_builders.h,
// drawn with Qt Charts by plot_render.h. Both the studio's plots area and the report use it.

#include <QColor>
#include <QList>
#include <QPointF>
#include <QString>
#include <QStringList>
#include <QVariant>
#include <QVector>

#include <optional>

namespace fovea::widgets {

struct PlotSeries {
  // Segments: the points taken in pairs, each pair one straight segment (bars drawn as wide
  // segments, error bars, threshold markers); one legend entry.
  enum class Style { Line, Dashed, Scatter, Area, Segments };
  QString name;
  QVector<QPointF> points;
  Style style = Style::Line;
  QColor color;            // invalid: the chart theme's next colour
  bool rightAxis = false;  // plotted against the secondary y axis
  double markerSize = 7.0;
  double lineWidth = 2.0;  // pen width (px) of lines and segments
};

struct PlotAxis {
  QString title;
  bool log = false;
  std::optional<double> min, max;
  QStringList categories;  // when set: category i is labelled at value i (a bar chart's names)
  int labelAngle = 0;      // degrees the category labels are turned (-90: read upwards, for long names)
};

struct PlotData {
  QString id;       // "fov-vs-gaze"
  QString title;    // "FOV vs gaze"
  QString caption;  // one sentence for figures: what is plotted and from which analysis
  PlotAxis x, y, y2;
  bool hasY2 = false;
  QVector<PlotSeries> series;
  // The numbers behind the plot: one header per column (with its unit), rows of numbers
  // (invalid QVariant = no value, e.g. outside a field) or text.
  QStringList columns;
  QVector<QVariantList> rows;
  QString summaryHtml;  // optional table shown under the chart (and in reports)
  QString source;       // the analysis and its parameters ("sweep --gaze-from -20 ...")

  bool isEmpty() const {
    for (const auto& s : series)
      if (!s.points.isEmpty()) return false;
    return true;
  }
};

// RFC 4180 CSV: the header, then the rows. Numbers with up to 10 significant digits; an
// empty cell for a missing value; text quoted when it needs to be.
QString plotCsv(const PlotData& plot);

}  // namespace fovea::widgets

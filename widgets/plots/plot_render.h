#pragma once
// Drawing a PlotData with Qt Charts, on screen and into files: PNG (raster), SVG (vector,
// via QSvgGenerator) and CSV (the plot's table). Exports always use the light theme on white
// so that figures print; the on-screen chart may follow the dark theme.

#include <QImage>
#include <QSize>
#include <QString>

#include "widgets/plots/plot_data.h"

QT_BEGIN_NAMESPACE
class QChart;
QT_END_NAMESPACE

namespace fovea::widgets {

// A new chart (the caller owns it) with the plot's series and axes.
QChart* buildChart(const PlotData& plot, bool dark = false);

// The plot drawn into an image of `size` logical pixels (scaled by `scale` for sharpness).
QImage renderPlotImage(const PlotData& plot, QSize size = QSize(900, 560), double scale = 2.0);

// Writes by the path's extension: .png, .svg or .csv. False with `error` set on failure
// (unknown extension, unwritable path); an existing file is only replaced by a complete one.
bool exportPlot(const PlotData& plot, const QString& path, QString* error = nullptr, QSize size = QSize(900, 560));

}  // namespace fovea::widgets

#pragma once
// Shared by the plot builders of each family (plots_*.cpp): JSON access that never throws,
// series and cell helpers, the palette. Internal to widgets/plots/.

#include <QColor>
#include <QString>
#include <QVariant>

#include <cmath>

#include <nlohmann/json.hpp>

#include "model/color/srgb.h"
#include "widgets/plots/plot_data.h"
#include "widgets/preferences.h"

namespace fovea::widgets::plots {

using Style = PlotSeries::Style;

// The colour the 3D view draws a wavelength in (model/color/srgb.h).
inline QColor wavelengthQColor(double nm) {
  const auto c = color::wavelengthColor(nm);
  return QColor::fromRgbF(float(c[0]), float(c[1]), float(c[2]));
}
inline QVariant cell(double v) {
  return std::isfinite(v) ? QVariant(v) : QVariant();
}
inline QString str(const nlohmann::json& j, const char* key) {
  if (!j.is_object() || !j.contains(key) || !j.at(key).is_string()) return {};
  return QString::fromStdString(j.at(key).get<std::string>());
}
inline const nlohmann::json& arr(const nlohmann::json& j, const char* key) {
  static const nlohmann::json empty = nlohmann::json::array();
  if (!j.is_object() || !j.contains(key) || !j.at(key).is_array()) return empty;
  return j.at(key);
}
inline void addPoint(PlotSeries& s, double x, double y) {
  if (std::isfinite(x) && std::isfinite(y)) s.points.append(QPointF(x, y));
}
inline PlotSeries series(const QString& name, Style style = Style::Line, QColor color = {}, bool right = false) {
  PlotSeries s;
  s.name = name;
  s.style = style;
  s.color = color;
  s.rightAxis = right;
  return s;
}
inline QString withUnit(const QString& what, const QString& unit) {
  return unit.isEmpty() ? what : what + " (" + unit + ")";
}
inline QString fmt(double v, int significant = 4) {
  return std::isfinite(v) ? QString::number(v, 'g', significant) : QStringLiteral("—");
}

inline const QColor kBlue(31, 119, 180), kOrange(255, 127, 14), kGreen(44, 160, 44), kRed(214, 39, 40),
    kPurple(148, 103, 189), kGray(120, 120, 120), kBrown(140, 86, 75);

// One builder per analysis family (plots_<family>.cpp), dispatched by plotsFromResult.
QList<PlotData> fromSweep(const nlohmann::json& r, const DisplayUnits& u, const QString& source);
QList<PlotData> fromSensitivity(const nlohmann::json& r, const DisplayUnits& u, const QString& source);
QList<PlotData> fromSelectivity(const nlohmann::json& r, const DisplayUnits& u, const QString& source);
QList<PlotData> fromGrating(const nlohmann::json& r, const DisplayUnits& u, const QString& source);
QList<PlotData> fromKogelnikVsRcwa(const nlohmann::json& r, const DisplayUnits& u, const QString& source);
QList<PlotData> fromResolution(const nlohmann::json& r, const DisplayUnits& u, const QString& source);
// The resolution result's "accommodation" part (--accommodation-d).
PlotData fromResolutionAccommodation(const nlohmann::json& accommodation, const QString& source);
QList<PlotData> fromLens(const nlohmann::json& r, const DisplayUnits& u, const QString& source);
QList<PlotData> fromTolerance(const nlohmann::json& r, const DisplayUnits& u, const QString& source);
QList<PlotData> fromFit(const nlohmann::json& r, const QString& source);

}  // namespace fovea::widgets::plots

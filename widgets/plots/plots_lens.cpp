// Plot of optimize-lens: the beam-shaping lens candidates.
#include <QColor>

#include <algorithm>
#include <cmath>
#include <map>

#include "model/json_numbers.h"
#include "widgets/plots/plot_builders.h"
#include "widgets/plots/plot_helpers.h"

namespace fovea::widgets::plots {

// ---- optimize-lens ------------------------------------------------------------------------
QList<PlotData> fromLens(const nlohmann::json& r, const DisplayUnits& u, const QString& source) {
  PlotData p;
  p.id = "lens-candidates";
  p.title = plotTitle(p.id);
  p.x.title = withUnit("focal length", u.lengthSymbol());
  p.y.title = "RMS pixel spot on the HOE (µm)";
  p.y.min = 0;
  std::map<double, PlotSeries> byDiameter;
  p.columns = {"part",
               withUnit("focal length", u.lengthSymbol()),
               withUnit("diameter", u.lengthSymbol()),
               withUnit("distance", u.lengthSymbol()),
               withUnit("decentre", u.lengthSymbol()),
               withUnit("tilt", u.angleSymbol()),
               "RMS spot (um)",
               "evaluations"};
  double fmin = INFINITY, fmax = -INFINITY;
  for (const auto& c : arr(r, "candidates")) {
    const double dia = jsonNumber(c, {"diameter_mm"}), f = u.lengthFromMm(jsonNumber(c, {"focal_length_mm"}));
    if (!byDiameter.count(dia))
      byDiameter[dia] = series(QString("Ø %1 stock lenses").arg(u.length(dia, 3)), Style::Scatter,
                               byDiameter.empty() ? kBlue : kOrange);
    addPoint(byDiameter[dia], f, jsonNumber(c, {"rms_spot_um"}));
    if (std::isfinite(f)) fmin = std::min(fmin, f), fmax = std::max(fmax, f);
    p.rows.append({QString::fromStdString(c.value("part", std::string())), cell(f), cell(u.lengthFromMm(dia)),
                   cell(u.lengthFromMm(jsonNumber(c, {"distance_mm"}))),
                   cell(u.lengthFromMm(jsonNumber(c, {"decenter_mm"}))),
                   cell(u.angleFromDeg(jsonNumber(c, {"tilt_deg"}))), cell(jsonNumber(c, {"rms_spot_um"})),
                   cell(jsonNumber(c, {"evaluations"}))});
  }
  for (auto& [d, s] : byDiameter) p.series.append(s);
  const double before = jsonNumber(r, {"rms_spot_um", "before"});
  if (std::isfinite(before) && fmin < fmax) {
    PlotSeries b = series("no lens", Style::Dashed, kGray);
    b.points = {QPointF(fmin, before), QPointF(fmax, before)};
    p.series.append(b);
  }
  p.caption = QString(
                  "Beam-shaping lens candidates (optimize-lens): the best placement of each stock lens. Best: "
                  "%1, RMS spot %2 µm → %3 µm (%4 % sharper).")
                  .arg(str(r, "vendor") + " " + str(r, "part"), fmt(before),
                       fmt(jsonNumber(r, {"rms_spot_um", "after"})), fmt(jsonNumber(r, {"improvement_percent"}), 3));
  p.source = source;
  return {p};
}

}  // namespace fovea::widgets::plots

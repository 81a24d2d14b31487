// Plot of the fit to measurements: normalised residuals before and after.
#include <QColor>

#include <algorithm>
#include <cmath>

#include "model/json_numbers.h"
#include "widgets/plots/plot_builders.h"
#include "widgets/plots/plot_helpers.h"

namespace fovea::widgets::plots {

// ---- fit ----------------------------------------------------------------------------------
// The fit document says which uncertainty to show: the scaled one when chi2/dof > 1.
bool scaledShown(const nlohmann::json& r) {
  return r.value("uncertainties_shown", std::string()) == "scaled";
}
double shownUncertainty(const nlohmann::json& r, const nlohmann::json& q) {
  return jsonNumber(q, {scaledShown(r) ? "uncertainty_scaled" : "uncertainty"});
}

QList<PlotData> fromFit(const nlohmann::json& r, const QString& source) {
  PlotData p;
  p.id = "fit-residuals";
  p.title = plotTitle(p.id);
  p.x.title = "target";
  p.y.title = "residual / σ";
  PlotSeries before = series("before the fit", Style::Scatter, kGray), after = series("fitted", Style::Scatter, kBlue),
             plus = series("+1 σ", Style::Dashed, kGreen), minus = series("−1 σ", Style::Dashed, kGreen);
  p.columns = {"target",
               "id",
               "observable",
               "unit",
               "value",
               "sigma",
               "model before",
               "model fitted",
               "normalised before",
               "normalised fitted",
               "source"};
  // The x axis names the targets by id (category i at x = i), turned to read upwards.
  int k = 0;
  for (const auto& t : arr(r, "targets")) {
    const double s = jsonNumber(t, {"sigma"}), v = jsonNumber(t, {"value"}), m0 = jsonNumber(t, {"initial_model"});
    const double n0 = (m0 - v) / s, n1 = jsonNumber(t, {"normalised"});
    addPoint(before, k, n0);
    addPoint(after, k, n1);
    p.x.categories << str(t, "id");
    ++k;
    p.rows.append({cell(k), str(t, "id"), str(t, "observable"), str(t, "unit"), cell(v), cell(s), cell(m0),
                   cell(jsonNumber(t, {"model"})), cell(n0), cell(n1), str(t, "source")});
  }
  p.x.labelAngle = -90;
  plus.points = {QPointF(-0.5, 1), QPointF(k - 0.5, 1)};
  minus.points = {QPointF(-0.5, -1), QPointF(k - 0.5, -1)};
  p.series = {before, after, plus, minus};
  QString html =
      "<table border='1' cellspacing='0' cellpadding='3'><tr><th>parameter</th><th>start</th><th>fitted</th>"
      "<th>± σ" +
      QString(scaledShown(r) ? " (scaled by √(χ²/dof))" : "") + "</th><th>bounds</th><th>note</th></tr>";
  for (const auto& q : arr(r, "parameters")) {
    QString note;
    for (const auto& w : arr(r, "warnings"))
      if (w.value("parameter", std::string()) == q.value("path", std::string()))
        note += QString::fromStdString(w.value("message", std::string())).toHtmlEscaped();
    const double sigma = shownUncertainty(r, q);
    html += QString(
                "<tr><td>%1 (%2)</td><td align='right'>%3</td><td align='right'>%4</td><td align='right'>%5</td>"
                "<td>%6 … %7</td><td>%8</td></tr>")
                .arg(str(q, "path").toHtmlEscaped(), str(q, "unit"), fmt(jsonNumber(q, {"initial"}), 6),
                     fmt(jsonNumber(q, {"fitted"}), 6), std::isfinite(sigma) ? fmt(sigma, 3) : QStringLiteral("—"),
                     fmt(jsonNumber(q, {"lower"}), 5), fmt(jsonNumber(q, {"upper"}), 5), note);
  }
  p.summaryHtml = html + "</table>";
  p.caption = QString(
                  "Fit to measurements: normalised residual of each target before (grey) and after (blue) the "
                  "fit; χ² %1 → %2 (%3 degrees of freedom, reduced χ² %6, %4 evaluations, %5).")
                  .arg(fmt(jsonNumber(r, {"chi2_initial"})), fmt(jsonNumber(r, {"chi2"})), fmt(jsonNumber(r, {"dof"})),
                       fmt(jsonNumber(r, {"evaluations"})), str(r, "algorithm"), fmt(jsonNumber(r, {"reduced_chi2"})));
  p.source = source;
  return {p};
}

}  // namespace fovea::widgets::plots

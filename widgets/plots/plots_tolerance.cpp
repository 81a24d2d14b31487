// Plots of the tolerance analysis: yield with its interval, sensitivity ranking, one
// histogram per per-trial figure.
#include <QColor>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "model/json_numbers.h"
#include "widgets/plots/plot_builders.h"
#include "widgets/plots/plot_helpers.h"

namespace fovea::widgets::plots {

namespace {

// The per-trial figures of a tolerance run (model/analysis/tolerance_spec.h, in output order).
struct ToleranceFigure {
  const char* name;
  const char* label;
  char unit;  // 'a' angle, 'l' length, '-' none
};
constexpr ToleranceFigure kToleranceFigures[] = {{"fov_min_deg", "smallest FOV over the gazes", 'a'},
                                                 {"fov_zero_gaze_deg", "FOV at zero gaze", 'a'},
                                                 {"eyebox_mm", "eye box", 'l'},
                                                 {"inset_error_deg", "foveal inset error", 'a'},
                                                 {"mean_efficiency", "mean efficiency", '-'}};

double toleranceDisplay(const ToleranceFigure& f, double v, const DisplayUnits& u) {
  return f.unit == 'a' ? u.angleFromDeg(v) : f.unit == 'l' ? u.lengthFromMm(v) : v;
}
QString toleranceUnit(const ToleranceFigure& f, const DisplayUnits& u) {
  return f.unit == 'a' ? u.angleSymbol() : f.unit == 'l' ? u.lengthSymbol() : QString();
}

PlotData yieldPlot(const nlohmann::json& r, const QString& source) {
  PlotData p;
  p.id = "tolerance-yield";
  p.title = plotTitle(p.id);
  p.x.title = "units passing (%)";
  p.x.min = 0;
  p.x.max = 100;
  p.y.categories = {"yield"};
  const nlohmann::json y = r.contains("yield") ? r["yield"] : nlohmann::json::object();
  const double v = 100 * jsonNumber(y, {"value"}), lo = 100 * jsonNumberAt(y, "confidence_95", 0),
               hi = 100 * jsonNumberAt(y, "confidence_95", 1), se = 100 * jsonNumber(y, {"standard_error"});
  const double target = 100 * jsonNumber(r, {"spec", "target_yield"});
  PlotSeries bar = series("yield", Style::Segments, kBlue);
  bar.lineWidth = 40;
  addPoint(bar, 0, 0);
  addPoint(bar, v, 0);
  PlotSeries ci = series("95 % confidence interval (Wilson)", Style::Segments, QColor(20, 20, 20));
  for (const auto& [a, b] : {std::pair{QPointF(lo, 0), QPointF(hi, 0)},
                             {QPointF(lo, -0.2), QPointF(lo, 0.2)},
                             {QPointF(hi, -0.2), QPointF(hi, 0.2)}}) {
    addPoint(ci, a.x(), a.y());
    addPoint(ci, b.x(), b.y());
  }
  PlotSeries tgt = series("target yield", Style::Dashed, kRed);
  addPoint(tgt, target, -0.5);
  addPoint(tgt, target, 0.5);
  p.series = {bar, ci, tgt};
  p.columns = {"yield (%)", "95 % low (%)", "95 % high (%)", "standard error (%)",
               "passed",    "trials",       "invalid units", "target yield (%)"};
  p.rows.append({cell(v), cell(lo), cell(hi), cell(se), cell(jsonNumber(y, {"passed"})),
                 cell(jsonNumber(y, {"trials"})), cell(jsonNumber(y, {"invalid_units"})), cell(target)});
  p.caption =
      QString(
          "Yield of %1 simulated units against the spec's pass criterion: %2 % (95 % Wilson interval %3 – "
          "%4 % over %5 independent samples; target %6 %) (tolerance, seed %7).")
          .arg(fmt(jsonNumber(y, {"trials"}), 8), fmt(v, 3), fmt(lo, 3), fmt(hi, 3),
               fmt(jsonNumber(y, {"independent_samples"}), 6), fmt(target, 3), fmt(jsonNumber(r, {"seed"}), 12));
  p.source = source;
  return p;
}

PlotData histogramPlot(const nlohmann::json& r, const ToleranceFigure& f, const DisplayUnits& u,
                       const QString& source) {
  PlotData p;
  p.id = QString("tolerance-") + f.name;
  p.title = plotTitle(p.id);
  const QString unit = toleranceUnit(f, u);
  p.x.title = withUnit(f.label, unit);
  p.y.title = "units";
  p.y.min = 0;
  const nlohmann::json d =
      r.contains("figures") && r["figures"].contains(f.name) ? r["figures"][f.name] : nlohmann::json::object();
  const nlohmann::json h = d.contains("histogram") ? d["histogram"] : nlohmann::json::object();
  const auto& edges = arr(h, "edges");
  const auto& counts = arr(h, "counts");
  PlotSeries steps = series("units per bin", Style::Line, kBlue);
  double top = 0;
  p.columns = {withUnit("bin from", unit), withUnit("bin to", unit), "units"};
  if (edges.size() == counts.size() + 1 && !counts.empty()) {
    addPoint(steps, toleranceDisplay(f, edges[0].get<double>(), u), 0);
    for (std::size_t b = 0; b < counts.size(); ++b) {
      const double x0 = toleranceDisplay(f, edges[b].get<double>(), u),
                   x1 = toleranceDisplay(f, edges[b + 1].get<double>(), u), c = counts[b].get<double>();
      addPoint(steps, x0, c);
      addPoint(steps, x1, c);
      top = std::max(top, c);
      p.rows.append({cell(x0), cell(x1), cell(c)});
    }
    addPoint(steps, toleranceDisplay(f, edges.back().get<double>(), u), 0);
  }
  p.series = {steps};
  QStringList bounds;
  const nlohmann::json pass =
      r.contains("spec") && r["spec"].contains("pass") ? r["spec"]["pass"] : nlohmann::json::object();
  if (pass.contains(f.name)) {
    PlotSeries th = series("pass threshold", Style::Segments, kRed);
    for (const char* k : {"min", "max"})
      if (pass[f.name].contains(k) && pass[f.name][k].is_number()) {
        const double x = toleranceDisplay(f, pass[f.name][k].get<double>(), u);
        addPoint(th, x, 0);
        addPoint(th, x, std::max(1.0, top * 1.05));
        bounds << QString("%1 %2").arg(QString(k) == "min" ? "≥" : "≤", fmt(x)) + (unit.isEmpty() ? "" : " " + unit);
      }
    p.series.append(th);
  }
  const double nominal = jsonNumber(r, {"nominal", f.name});
  if (std::isfinite(nominal)) {
    PlotSeries nom = series("nominal design", Style::Dashed, kGray);
    addPoint(nom, toleranceDisplay(f, nominal, u), 0);
    addPoint(nom, toleranceDisplay(f, nominal, u), std::max(1.0, top * 1.05));
    p.series.append(nom);
  }
  p.caption =
      QString(
          "Distribution of the %1 over %2 simulated units (20 bins): mean %3, std %4, p05 %5, p95 %6 %7; "
          "nominal %8%9 (tolerance).")
          .arg(f.label, fmt(jsonNumber(d, {"count"}), 8), fmt(toleranceDisplay(f, jsonNumber(d, {"mean"}), u)),
               fmt(toleranceDisplay(f, jsonNumber(d, {"std"}), u)),  // the units only scale
               fmt(toleranceDisplay(f, jsonNumber(d, {"p05"}), u)), fmt(toleranceDisplay(f, jsonNumber(d, {"p95"}), u)),
               unit, fmt(toleranceDisplay(f, nominal, u)),
               bounds.isEmpty() ? QString("; not in the pass criterion") : "; passes when " + bounds.join(" and "));
  p.source = source;
  return p;
}

PlotData rankingPlot(const nlohmann::json& r, const QString& source) {
  PlotData p;
  p.id = "tolerance-ranking";
  p.title = plotTitle(p.id);
  const nlohmann::json sens = r.contains("sensitivity") ? r["sensitivity"] : nlohmann::json::object();
  const QString by = str(sens, "ranked_by");
  p.x.title = "variance-based sensitivity index on " + (by.isEmpty() ? QString("failure") : by);
  p.columns = {"rank", "parameter", "total index", "total index SE", "first-order index", "first-order index SE"};
  // The outputs' entries in the ranking's order (most influential first, drawn at the top).
  std::vector<const nlohmann::json*> rows;
  const nlohmann::json outputs = sens.contains("outputs") && sens["outputs"].contains(by.toStdString())
                                     ? sens["outputs"][by.toStdString()]
                                     : nlohmann::json::array();
  for (const auto& name : arr(sens, "ranking"))
    for (const auto& e : outputs)
      if (e.value("parameter", std::string()) == name) rows.push_back(&e);
  PlotSeries total = series("total index (Jansen)", Style::Segments, kBlue),
             first = series("first-order index (Saltelli)", Style::Segments, kOrange),
             err = series("± standard error (bootstrap)", Style::Segments, QColor(20, 20, 20));
  total.lineWidth = 9;
  first.lineWidth = 4;
  err.lineWidth = 1.5;
  const int n = static_cast<int>(rows.size());
  for (int i = 0; i < n; ++i) {
    const nlohmann::json& e = *rows[i];
    const double y = n - 1 - i;  // rank 1 at the top
    p.y.categories.prepend(QString::fromStdString(e.value("parameter", std::string())));
    const double t = jsonNumber(e, {"total"}), tse = jsonNumber(e, {"total_se"}), s1 = jsonNumber(e, {"first_order"}),
                 s1se = jsonNumber(e, {"first_order_se"});
    addPoint(total, 0, y + 0.12);
    addPoint(total, t, y + 0.12);
    addPoint(first, 0, y - 0.18);
    addPoint(first, s1, y - 0.18);
    if (std::isfinite(tse)) {
      addPoint(err, t - tse, y + 0.12);
      addPoint(err, t + tse, y + 0.12);
    }
    if (std::isfinite(s1se)) {
      addPoint(err, s1 - s1se, y - 0.18);
      addPoint(err, s1 + s1se, y - 0.18);
    }
    p.rows.append({cell(i + 1), QString::fromStdString(e.value("parameter", std::string())), cell(t), cell(tse),
                   cell(s1), cell(s1se)});
  }
  p.series = {total, first, err};
  QString html =
      "<table border='1' cellspacing='0' cellpadding='3'><tr><th>rank</th><th>parameter</th><th>total index</th>"
      "<th>first-order index</th></tr>";
  // A row is resolved when its total index stands clear of zero (more than two standard errors);
  // the others are named once under the table instead of as rows of "0 ± 0".
  QStringList unresolved;
  int shown = 0;
  for (const QVariantList& row : p.rows) {
    const double t = row[2].toDouble(), tse = row[3].toDouble();
    if (!(t > 0.005 && t > 2 * tse)) {
      unresolved << row[1].toString().toHtmlEscaped();
      continue;
    }
    ++shown;
    html += QString(
                "<tr><td align='right'>%1</td><td>%2</td><td align='right'>%3 ± %4</td>"
                "<td align='right'>%5 ± %6</td></tr>")
                .arg(row[0].toString(), row[1].toString().toHtmlEscaped(), fmt(row[2].toDouble(), 2),
                     fmt(row[3].toDouble(), 2), fmt(row[4].toDouble(), 2), fmt(row[5].toDouble(), 2));
  }
  p.summaryHtml = shown > 0 ? html + "</table>" : QString();
  if (!unresolved.isEmpty())
    p.summaryHtml +=
        QString(
            "<p>Not resolved with %1 base samples (total index within two standard errors of 0, or exactly 0 when "
            "re-drawing that tolerance changed no unit's result): %2. More trials tell them apart.</p>")
            .arg(fmt(jsonNumber(sens, {"base_samples"}), 6), unresolved.join(", "));
  p.caption = QString(
                  "Which tolerance drives %1: total (Jansen 1999) and first-order (Saltelli et al. 2010) "
                  "variance-based indices of each parameter from the Saltelli design (%2 base samples), with "
                  "bootstrap standard errors (%3 resamples); ranked by the total index (tolerance).")
                  .arg(by.isEmpty() ? QString("failure") : by, fmt(jsonNumber(sens, {"base_samples"}), 6),
                       fmt(jsonNumber(sens, {"bootstrap_resamples"}), 6));
  p.source = source;
  return p;
}

}  // namespace

QList<PlotData> fromTolerance(const nlohmann::json& r, const DisplayUnits& u, const QString& source) {
  QList<PlotData> out{yieldPlot(r, source), rankingPlot(r, source)};
  for (const ToleranceFigure& f : kToleranceFigures) out << histogramPlot(r, f, u, source);
  return out;
}

}  // namespace fovea::widgets::plots

#include "app/studio/report_tolerance.h"

#include <cmath>
#include <map>
#include <string>

#include "app/studio/report_html.h"
#include "model/json_numbers.h"
#include "widgets/analyses/analysis_summary.h"
#include "widgets/number_text.h"
#include "widgets/plots/plot_builders.h"

namespace fovea::studio {

using report_html::g;
using report_html::pct;

namespace {
QString text(const nlohmann::json& j, const char* key, const char* fallback = "") {
  return QString::fromStdString(j.is_object() && j.contains(key) && j[key].is_string() ? j[key].get<std::string>()
                                                                                       : std::string(fallback))
      .toHtmlEscaped();
}

// "normal, σ 0.2" / "uniform, ±0.002" / "truncated normal, σ 1, |x| ≤ 2"
QString distributionText(const nlohmann::json& p) {
  const QString d = text(p, "distribution", "normal");
  QString t = d == "uniform"
                  ? QString("uniform, ± %1").arg(g(jsonNumber(p, {"half_width"})))
                  : QString("%1, σ %2")
                        .arg(d == "truncated_normal" ? "truncated normal" : "normal", g(jsonNumber(p, {"sigma"})));
  if (d == "truncated_normal") t += QString(", |x − mean| ≤ %1").arg(g(jsonNumber(p, {"limit"})));
  if (std::isfinite(jsonNumber(p, {"mean"})) && jsonNumber(p, {"mean"}) != 0)
    t += QString(", mean %1").arg(g(jsonNumber(p, {"mean"})));
  return t;
}

// The inverse row of a tolerance that does not reach the target alone: how far the scan got.
QString unreachedText(const nlohmann::json& e) {
  const std::string why = e.value("stopped_by", std::string());
  if (why == "effective_samples_at_spec") return "not resolved: too few independent trials to reweight";
  if (!e.contains("best_yield")) return "not reached alone";
  const QString best = QString("not reached alone: at most %1 down to × %2 of the spec")
                           .arg(pct(jsonNumber(e, {"best_yield"})), g(jsonNumber(e, {"smallest_scale"}), 2));
  return why == "effective_samples" ? best + " (then fewer than 20 effective trials)" : best;
}

}  // namespace

QString toleranceSpecTableHtml(const nlohmann::json& r) {
  const nlohmann::json spec = r.contains("spec") ? r["spec"] : nlohmann::json::object();
  std::map<std::string, nlohmann::json> inverse;
  if (r.contains("inverse") && r["inverse"].contains("parameters"))
    for (const auto& e : r["inverse"]["parameters"]) inverse[e.value("parameter", std::string())] = e;
  int reached = 0, inverted = 0;
  QString h =
      "<table border='1' cellspacing='0' cellpadding='4' width='100%'><tr><th align='left'>tolerance</th>"
      "<th align='left'>what it varies</th><th align='left'>distribution</th>"
      "<th align='left'>width for the target yield</th></tr>";
  for (const auto& p : spec.value("parameters", nlohmann::json::array())) {
    const std::string name = p.value("name", p.value("path", p.value("kind", std::string())));
    QString kind = text(p, "kind", "scene");
    const QString what = kind == "scene" ? "offset of " + text(p, "path") : kind.replace('_', ' ');
    QString inv = "—";
    if (inverse.count(name)) {
      const auto& e = inverse[name];
      inv = e.value("achievable", false)
                ? QString("%1 (× %2 of the spec; yield %3 over %4 effective trials)")
                      .arg(g(jsonNumber(e, {"width"}), 3), g(jsonNumber(e, {"scale"}), 3),
                           pct(jsonNumber(e, {"yield"})), g(jsonNumber(e, {"effective_samples"}), 4))
                : unreachedText(e);
      reached += e.value("achievable", false) ? 1 : 0;
      ++inverted;
    }
    h += QString("<tr><td>%1</td><td>%2</td><td>%3</td><td>%4</td></tr>")
             .arg(QString::fromStdString(name).toHtmlEscaped(), what, distributionText(p), inv);
  }
  h += "</table>";
  // Said once under the table rather than in every row: no single tolerance reaches the target.
  if (inverted > 0 && reached == 0)
    h += QString(
             "<p>No single tolerance reaches the target yield %1 when it alone is tightened (the others at spec): "
             "the failures come from several tolerances together, or the trials are too few to tell (the scan stops "
             "where fewer than 20 effective trials remain). Tighten several at once, or run more trials.</p>")
             .arg(pct(jsonNumber(r, {"spec", "target_yield"})));
  const nlohmann::json gaze = spec.value("gaze", nlohmann::json::object());
  QStringList pass;
  const nlohmann::json bounds = spec.value("pass", nlohmann::json::object());
  for (const auto& [figure, b] : bounds.items()) {
    if (b.contains("min"))
      pass << QString("%1 ≥ %2").arg(QString::fromStdString(figure)).arg(g(jsonNumber(b, {"min"})));
    if (b.contains("max"))
      pass << QString("%1 ≤ %2").arg(QString::fromStdString(figure)).arg(g(jsonNumber(b, {"max"})));
  }
  h +=
      QString(
          "<p>Every unit is run at gazes %1 … %2 deg in steps of %3 deg along %4, the dynamic eye box by %5 with the "
          "<b>%6</b> compensator%7. A unit passes when %8. %9 trials, seed %10.</p>")
          .arg(g(jsonNumber(gaze, {"from_deg"})), g(jsonNumber(gaze, {"to_deg"})), g(jsonNumber(gaze, {"step_deg"})),
               text(gaze, "axis", "yaw"), text(spec, "shift", "hoe"), text(spec, "compensator", "refind"),
               spec.contains("wavelength_nm") ? QString(", traced at %1 nm").arg(g(jsonNumber(spec, {"wavelength_nm"})))
                                              : QString(),
               pass.isEmpty() ? QString("(no bound)") : pass.join(" and ").toHtmlEscaped(),
               g(jsonNumber(r, {"trials"}), 10), g(jsonNumber(r, {"seed"}), 12));
  return h;
}

ReportSection toleranceReportSection(const nlohmann::json& r, const widgets::DisplayUnits& u) {
  ReportSection s;
  s.heading = "Tolerance";
  if (!r.is_object() || r.value("format", std::string()) != "fovea-tolerance-result") return s;
  const nlohmann::json y = r["yield"];
  s.introHtml =
      QString(
          "Monte Carlo tolerancing of the design (docs/tolerancing.md): yield <b>%1</b> (95 % Wilson "
          "interval %2 – %3 over %9; %4 of %5 units pass; target %6).%7</p>%8<p>")
          .arg(pct(jsonNumber(y, {"value"})), pct(jsonNumberAt(y, "confidence_95", 0)),
               pct(jsonNumberAt(y, "confidence_95", 1)), g(jsonNumber(y, {"passed"}), 10),
               g(jsonNumber(y, {"trials"}), 10), pct(jsonNumber(r, {"spec", "target_yield"})),
               jsonNumber(y, {"invalid_units"}) > 0 ? QString(" %1 units broke the scene rules and count as failed.")
                                                          .arg(g(jsonNumber(y, {"invalid_units"}), 10))
                                                    : QString(),
               toleranceSpecTableHtml(r), widgets::toleranceIntervalBasis(y));
  for (const widgets::PlotData& p : widgets::plotsFromResult("tolerance", r, u)) addPlotFigure(s.figures, p);
  return s;
}

}  // namespace fovea::studio

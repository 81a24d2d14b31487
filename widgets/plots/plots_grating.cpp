// Plots of the HOE efficiency analyses: selectivity, grating, Kogelnik vs RCWA.
#include <QColor>

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "model/json_numbers.h"
#include "widgets/plots/plot_builders.h"
#include "widgets/plots/plot_helpers.h"

namespace fovea::widgets::plots {

// ---- selectivity --------------------------------------------------------------------------
QList<PlotData> fromSelectivity(const nlohmann::json& r, const DisplayUnits& u, const QString& source) {
  PlotData ang;
  ang.id = "efficiency-vs-angle";
  ang.title = plotTitle(ang.id);
  ang.x.title = withUnit("probe detuning from the projector's direction", u.angleSymbol());
  ang.y.title = "diffraction efficiency";
  ang.y.min = 0;
  ang.y.max = 1;
  PlotData spec;
  spec.id = "efficiency-vs-wavelength";
  spec.title = plotTitle(spec.id);
  spec.x.title = "probe wavelength (nm)";
  spec.y.title = "diffraction efficiency";
  spec.y.min = 0;
  spec.y.max = 1;
  spec.columns = {"layer", "wavelength (nm)", "efficiency", "xi"};
  ang.columns = {withUnit("detuning", u.angleSymbol())};
  const auto& layers = arr(r, "layers");
  std::vector<const nlohmann::json*> angleCurves;
  QStringList summary;
  for (const auto& l : layers) {
    const QString name = str(l, "name");
    const double probe = jsonNumber(l, {"probe_wavelength_nm"});
    const QString label = QString("%1 layer (%2 nm)").arg(name, fmt(probe));
    PlotSeries a = series(label, Style::Line, wavelengthQColor(probe));
    for (const auto& s : arr(l, "angle"))
      addPoint(a, u.angleFromDeg(jsonNumber(s, {"detuning_deg"})), jsonNumber(s, {"efficiency"}));
    PlotSeries w = series(label, Style::Line, wavelengthQColor(probe));
    for (const auto& s : arr(l, "spectrum")) {
      addPoint(w, jsonNumber(s, {"wavelength_nm"}), jsonNumber(s, {"efficiency"}));
      spec.rows.append({name, cell(jsonNumber(s, {"wavelength_nm"})), cell(jsonNumber(s, {"efficiency"})),
                        cell(jsonNumber(s, {"xi"}))});
    }
    ang.series.append(a);
    spec.series.append(w);
    ang.columns << withUnit(name + " efficiency", {});
    angleCurves.push_back(&arr(l, "angle"));
    summary << QString("%1: η %2 at the nominal probe, peak %3 at %4, FWHM %5 / %6 nm")
                   .arg(name, fmt(jsonNumber(l, {"nominal_efficiency"}), 3),
                        fmt(jsonNumber(l, {"peak_angle_efficiency"}), 3),
                        u.angle(jsonNumber(l, {"peak_detuning_deg"}), 3),
                        u.angle(jsonNumber(l, {"angular_fwhm_deg"}), 3), fmt(jsonNumber(l, {"spectral_fwhm_nm"}), 3));
  }
  // Wide table: the layers share the detuning samples.
  const std::size_t n = angleCurves.empty() ? 0 : angleCurves.front()->size();
  for (std::size_t i = 0; i < n; ++i) {
    QVariantList row{cell(u.angleFromDeg(jsonNumber((*angleCurves.front())[i], {"detuning_deg"})))};
    for (const auto* c : angleCurves) row << (i < c->size() ? cell(jsonNumber((*c)[i], {"efficiency"})) : QVariant());
    ang.rows.append(row);
  }
  const auto pt = r.contains("point_mm") ? r["point_mm"] : nlohmann::json::array();
  const QString where =
      pt.size() == 2
          ? QString("at plate point (%1, %2)").arg(u.length(pt[0].get<double>()), u.length(pt[1].get<double>()))
          : QString();
  ang.caption = QString(
                    "Angular selectivity of each HOE layer alone %1: efficiency as the projector's probe is "
                    "tilted in its plane of incidence (Kogelnik, selectivity). %2.")
                    .arg(where, summary.join("; "));
  spec.caption = QString(
                     "Spectral selectivity of each HOE layer alone %1 at the nominal probe direction "
                     "(Kogelnik, selectivity).")
                     .arg(where);
  ang.source = spec.source = source;
  return {ang, spec};
}

// ---- grating ------------------------------------------------------------------------------
QList<PlotData> fromGrating(const nlohmann::json& r, const DisplayUnits& u, const QString& source) {
  PlotData p;
  p.id = "efficiency-vs-angle";
  p.title = plotTitle(p.id);
  p.x.title = withUnit("probe detuning (inside the film)", u.angleSymbol());
  p.y.title = "diffraction efficiency";
  p.y.min = 0;
  p.y.max = 1;
  const bool rcwa = r.contains("models") && r["models"].size() > 1;
  PlotSeries k = series("Kogelnik", Style::Line, kBlue), w = series("RCWA", Style::Dashed, kRed);
  p.columns = {withUnit("probe angle", u.angleSymbol()), withUnit("detuning", u.angleSymbol()), "Kogelnik efficiency"};
  if (rcwa) p.columns << "RCWA efficiency";
  for (const auto& s : arr(r, "samples")) {
    const double x = u.angleFromDeg(jsonNumber(s, {"detuning_deg"}));
    addPoint(k, x, jsonNumber(s, {"kogelnik_efficiency"}));
    QVariantList row{cell(u.angleFromDeg(jsonNumber(s, {"probe_deg"}))), cell(x),
                     cell(jsonNumber(s, {"kogelnik_efficiency"}))};
    if (rcwa) {
      addPoint(w, x, jsonNumber(s, {"rcwa_efficiency"}));
      row << cell(jsonNumber(s, {"rcwa_efficiency"}));
    }
    p.rows.append(row);
  }
  p.series = {k};
  if (rcwa) p.series.append(w);
  const nlohmann::json c = r.contains("center") ? r["center"] : nlohmann::json::object();
  p.caption = QString(
                  "Planar %1 grating: efficiency vs probe angle around the request's probe (η %2, ν %3, "
                  "ξ %4 there)%5.")
                  .arg(str(c, "type"), fmt(jsonNumber(c, {"efficiency"}), 4), fmt(jsonNumber(c, {"nu"}), 4),
                       fmt(jsonNumber(c, {"xi"}), 4), rcwa ? ", Kogelnik against converged RCWA" : "");
  p.source = source;
  return {p};
}

// ---- kogelnik vs rcwa ---------------------------------------------------------------------
QList<PlotData> fromKogelnikVsRcwa(const nlohmann::json& r, const DisplayUnits& /*u*/, const QString& source) {
  PlotData p;
  p.id = "time-vs-error";
  p.title = plotTitle(p.id);
  p.x.title = "validity parameter ρ = λ²/(Λ² n0 n1)";
  p.x.log = true;
  p.y.title = "|η Kogelnik − η RCWA|";
  p.y.log = true;
  constexpr double kFloor = 1e-7;  // zero errors are drawn at the floor of the log axis
  p.y.min = kFloor;
  p.y.max = 1.0;
  p.columns = {"geometry",
               "thickness (um)",
               "n1",
               "xi",
               "rho",
               "Klein Q",
               "Kogelnik efficiency",
               "RCWA efficiency",
               "abs error",
               "Kogelnik (ns)",
               "RCWA converged (ms)"};
  std::map<std::string, PlotSeries> byGeometry;
  std::vector<std::string> order;
  const QColor palette[] = {kBlue, kOrange, kGreen, kRed, kPurple, kBrown, kGray};
  for (const auto& s : arr(r, "points")) {
    const std::string g = s.value("geometry", std::string("?"));
    if (!byGeometry.count(g)) {
      byGeometry[g] = series(QString::fromStdString(g), Style::Scatter, palette[order.size() % 7]);
      order.push_back(g);
    }
    addPoint(byGeometry[g], jsonNumber(s, {"rho"}), std::max(kFloor, jsonNumber(s, {"abs_error"})));
    p.rows.append({QString::fromStdString(g), cell(jsonNumber(s, {"thickness_um"})), cell(jsonNumber(s, {"n1"})),
                   cell(jsonNumber(s, {"xi_target"})), cell(jsonNumber(s, {"rho"})), cell(jsonNumber(s, {"klein_q"})),
                   cell(jsonNumber(s, {"kogelnik_efficiency"})), cell(jsonNumber(s, {"rcwa_efficiency"})),
                   cell(jsonNumber(s, {"abs_error"})), cell(jsonNumber(s, {"kogelnik_ns"})),
                   cell(jsonNumber(s, {"rcwa_ms"}))});
  }
  for (const auto& g : order) p.series.append(byGeometry[g]);
  QString html =
      "<table border='1' cellspacing='0' cellpadding='3'><tr><th>ρ range</th><th>points</th><th>max |Δη|</th>"
      "<th>median |Δη|</th><th>max |Δη| at ν ≤ π/2</th><th>Kogelnik (ns)</th><th>RCWA (ms)</th>"
      "<th>RCWA / Kogelnik time</th></tr>";
  for (const auto& b : arr(r, "by_rho")) {
    const double hi = jsonNumber(b, {"rho_max"});
    const double ratio = jsonNumber(b, {"mean_rcwa_ms"}) * 1e6 / jsonNumber(b, {"mean_kogelnik_ns"});
    html += QString(
                "<tr><td>%1 – %2</td><td align='right'>%3</td><td align='right'>%4</td><td align='right'>%5</td>"
                "<td align='right'>%6</td><td align='right'>%7</td><td align='right'>%8</td>"
                "<td align='right'>%9</td></tr>")
                .arg(fmt(jsonNumber(b, {"rho_min"})), std::isfinite(hi) ? fmt(hi) : QStringLiteral("∞"),
                     fmt(jsonNumber(b, {"points"})), QString::number(jsonNumber(b, {"max_error"}), 'e', 2),
                     QString::number(jsonNumber(b, {"median_error"}), 'e', 2),
                     QString::number(jsonNumber(b, {"max_error_weak"}), 'e', 2),
                     fmt(jsonNumber(b, {"mean_kogelnik_ns"}), 3), fmt(jsonNumber(b, {"mean_rcwa_ms"}), 3),
                     std::isfinite(ratio) ? QString::number(ratio, 'e', 1) : QStringLiteral("—"));
  }
  p.summaryHtml = html + "</table>";
  p.caption = QString(
                  "Kogelnik's two-wave theory against converged RCWA (%1 grid, %2 points): the error vs the "
                  "validity parameter ρ per grating geometry; the table gives the error and the run time of "
                  "each model by ρ decade (errors below 1e-7 drawn at 1e-7).")
                  .arg(str(r, "grid").isEmpty() ? "quick" : str(r, "grid"))
                  .arg(arr(r, "points").size());
  p.source = source;
  return {p};
}

}  // namespace fovea::widgets::plots

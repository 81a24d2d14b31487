#include "widgets/plots/plot_builders.h"

#include <QColor>

#include <algorithm>
#include <cmath>
#include <map>

#include "model/color/srgb.h"
#include "model/json_numbers.h"

namespace fovea::widgets {

namespace {

using Style = PlotSeries::Style;

// The colour the 3D view draws a wavelength in (model/color/srgb.h).
QColor wavelengthQColor(double nm) {
  const auto c = color::wavelengthColor(nm);
  return QColor::fromRgbF(float(c[0]), float(c[1]), float(c[2]));
}
QVariant cell(double v) {
  return std::isfinite(v) ? QVariant(v) : QVariant();
}
QString str(const nlohmann::json& j, const char* key) {
  if (!j.is_object() || !j.contains(key) || !j.at(key).is_string()) return {};
  return QString::fromStdString(j.at(key).get<std::string>());
}
const nlohmann::json& arr(const nlohmann::json& j, const char* key) {
  static const nlohmann::json empty = nlohmann::json::array();
  if (!j.is_object() || !j.contains(key) || !j.at(key).is_array()) return empty;
  return j.at(key);
}
void addPoint(PlotSeries& s, double x, double y) {
  if (std::isfinite(x) && std::isfinite(y)) s.points.append(QPointF(x, y));
}
PlotSeries series(const QString& name, Style style = Style::Line, QColor color = {}, bool right = false) {
  PlotSeries s;
  s.name = name;
  s.style = style;
  s.color = color;
  s.rightAxis = right;
  return s;
}
QString withUnit(const QString& what, const QString& unit) {
  return unit.isEmpty() ? what : what + " (" + unit + ")";
}
QString fmt(double v, int significant = 4) {
  return std::isfinite(v) ? QString::number(v, 'g', significant) : QStringLiteral("—");
}

const QColor kBlue(31, 119, 180), kOrange(255, 127, 14), kGreen(44, 160, 44), kRed(214, 39, 40), kPurple(148, 103, 189),
    kGray(120, 120, 120), kBrown(140, 86, 75);

// ---- sweep --------------------------------------------------------------------------------
QList<PlotData> fromSweep(const nlohmann::json& r, const DisplayUnits& u, const QString& source) {
  const QString axis = str(r, "axis").isEmpty() ? QStringLiteral("yaw") : str(r, "axis");
  const QString gazeCol = withUnit("gaze " + axis, u.angleSymbol());
  const nlohmann::json eb = r.contains("eyebox") ? r["eyebox"] : nlohmann::json::object();
  const double eyebox = jsonNumber(r, {"eyebox_mm"});
  const auto gr = eb.contains("gaze_range_deg") ? eb["gaze_range_deg"] : nlohmann::json::array();
  const auto tr = eb.contains("travel_mm") ? eb["travel_mm"] : nlohmann::json::array();
  const QString eyeboxText = QString("Eye box %1 over gaze %2 .. %3 %4 (FOV within the tolerance of the zero-gaze FOV)")
                                 .arg(u.length(eyebox))
                                 .arg(gr.size() == 2 ? fmt(u.angleFromDeg(gr[0].get<double>())) : "—")
                                 .arg(gr.size() == 2 ? fmt(u.angleFromDeg(gr[1].get<double>())) : "—")
                                 .arg(u.angleSymbol());

  PlotData fov;
  fov.id = "fov-vs-gaze";
  fov.title = plotTitle(fov.id);
  fov.x.title = gazeCol;
  fov.y.title = withUnit("retinal FOV", u.angleSymbol());
  fov.y.min = 0;
  PlotSeries h = series("horizontal", Style::Line, kBlue), v = series("vertical", Style::Line, kOrange),
             d = series("diagonal", Style::Dashed, kGreen);
  PlotData travel;
  travel.id = "travel-vs-gaze";
  travel.title = plotTitle(travel.id);
  travel.x.title = gazeCol;
  travel.y.title = withUnit("position", u.lengthSymbol());
  PlotSeries shift = series(axis == "pitch" ? "optimal HOE shift (local y)" : "optimal HOE shift (local x)",
                            Style::Line, kBlue),
             pupil = series("pupil centre", Style::Dashed, kGray);
  fov.columns = {gazeCol,
                 withUnit("FOV horizontal", u.angleSymbol()),
                 withUnit("FOV vertical", u.angleSymbol()),
                 withUnit("FOV diagonal", u.angleSymbol()),
                 "mean efficiency",
                 "efficiency uniformity"};
  travel.columns = {gazeCol, withUnit("HOE shift", u.lengthSymbol()), withUnit("pupil position", u.lengthSymbol())};
  for (const auto& s : arr(r, "samples")) {
    const double g = u.angleFromDeg(jsonNumber(s, {"gaze_deg"}));
    const double fh = u.angleFromDeg(jsonNumber(s, {"fov_deg", "horizontal"})),
                 fv = u.angleFromDeg(jsonNumber(s, {"fov_deg", "vertical"})),
                 fd = u.angleFromDeg(jsonNumber(s, {"fov_deg", "diagonal"}));
    addPoint(h, g, fh);
    addPoint(v, g, fv);
    addPoint(d, g, fd);
    fov.rows.append({cell(g), cell(fh), cell(fv), cell(fd), cell(jsonNumber(s, {"mean_efficiency"})),
                     cell(jsonNumber(s, {"efficiency_uniformity"}))});
    const double sh = u.lengthFromMm(jsonNumber(s, {"hoe_shift_mm"})),
                 pp = u.lengthFromMm(jsonNumber(s, {"pupil_position_mm"}));
    addPoint(shift, g, sh);
    addPoint(pupil, g, pp);
    travel.rows.append({cell(g), cell(sh), cell(pp)});
  }
  fov.series = {h, v, d};
  travel.series = {shift, pupil};
  fov.caption = QString("Retinal FOV vs gaze %1 with the FOV-maximising HOE shift at each gaze (sweep). %2.")
                    .arg(axis, eyeboxText);
  travel.caption = QString(
                       "HOE travel x_p vs gaze %1: the lateral HOE shift that maximises the FOV, beside the pupil "
                       "centre's position. Travel at the eye-box borders %2 .. %3.")
                       .arg(axis)
                       .arg(tr.size() == 2 ? u.length(tr[0].get<double>()) : "—")
                       .arg(tr.size() == 2 ? u.length(tr[1].get<double>()) : "—");
  fov.source = travel.source = source;
  return {fov, travel};
}

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

// ---- resolution ---------------------------------------------------------------------------
QList<PlotData> fromResolution(const nlohmann::json& r, const DisplayUnits& u, const QString& source) {
  PlotData p;
  p.id = "resolution-vs-eccentricity";
  p.title = plotTitle(p.id);
  p.x.title = withUnit("eccentricity", u.angleSymbol());
  p.y.title = "resolution (cycles per degree)";
  p.y.min = 0;
  PlotSeries perceived = series("perceived", Style::Line, QColor(20, 20, 20)),
             foveal = series("foveal display", Style::Line, kBlue),
             peripheral = series("peripheral display", Style::Line, kOrange),
             optical = series("foveal optics (MTF30, traced)", Style::Dashed, kPurple),
             eye = series("eye limit", Style::Dashed, kGray);
  p.columns = {withUnit("eccentricity", u.angleSymbol()),
               "foveal (cpd)",
               "peripheral (cpd)",
               "optical limit (cpd)",
               "optical limit model (cpd)",
               "perceived (cpd)",
               "foveal shown"};
  const double eyeLimit = jsonNumber(r, {"eye_limit_cpd"});
  double xmin = INFINITY, xmax = -INFINITY;
  for (const auto& s : arr(r, "samples")) {
    const double e = u.angleFromDeg(jsonNumber(s, {"eccentricity_deg"}));
    addPoint(perceived, e, jsonNumber(s, {"perceived_cpd"}));
    addPoint(foveal, e, jsonNumber(s, {"foveal_cpd"}));
    addPoint(peripheral, e, jsonNumber(s, {"peripheral_cpd"}));
    addPoint(optical, e, jsonNumber(s, {"optical_limit_cpd"}));
    if (std::isfinite(e)) xmin = std::min(xmin, e), xmax = std::max(xmax, e);
    p.rows.append({cell(e), cell(jsonNumber(s, {"foveal_cpd"})), cell(jsonNumber(s, {"peripheral_cpd"})),
                   cell(jsonNumber(s, {"optical_limit_cpd"})), cell(jsonNumber(s, {"optical_limit_model_cpd"})),
                   cell(jsonNumber(s, {"perceived_cpd"})),
                   s.contains("foveal_shown") && s["foveal_shown"].is_boolean()
                       ? QVariant(s["foveal_shown"].get<bool>())
                       : QVariant()});
  }
  if (std::isfinite(eyeLimit) && xmin < xmax) eye.points = {QPointF(xmin, eyeLimit), QPointF(xmax, eyeLimit)};
  perceived.markerSize = 0;
  p.series = {foveal, peripheral, optical, eye, perceived};
  const auto g = r.contains("gaze_deg") ? r["gaze_deg"] : nlohmann::json::array();
  p.caption = QString(
                  "Angular resolution vs eccentricity at gaze (%1, %2) %3: the foveal micro-OLED, the "
                  "peripheral projector, the ray-traced optical limit of the foveal combiner and what the eye "
                  "perceives (resolution). Peripheral pixel integral %4 of %5 pixels.")
                  .arg(g.size() == 2 ? fmt(u.angleFromDeg(g[0].get<double>())) : "—")
                  .arg(g.size() == 2 ? fmt(u.angleFromDeg(g[1].get<double>())) : "—")
                  .arg(u.angleSymbol())
                  .arg(fmt(jsonNumber(r, {"peripheral_pixel_integral"}), 4))
                  .arg(fmt(jsonNumber(r, {"pixels_horizontal"}), 5));
  p.source = source;
  return {p};
}

// ---- kogelnik vs rcwa ---------------------------------------------------------------------
QList<PlotData> fromKogelnikVsRcwa(const nlohmann::json& r, const DisplayUnits&, const QString& source) {
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

// ---- sensitivity --------------------------------------------------------------------------
QList<PlotData> fromSensitivity(const nlohmann::json& r, const DisplayUnits& u, const QString& source) {
  PlotData p;
  p.id = "sensitivity";
  p.title = plotTitle(p.id);
  const QString param = str(r, "parameter");
  p.x.title = param;
  p.y.title = withUnit("retinal FOV", u.angleSymbol());
  p.y.min = 0;
  p.hasY2 = true;
  p.y2.title = "efficiency";
  p.y2.min = 0;
  p.y2.max = 1;
  PlotSeries h = series("FOV horizontal", Style::Line, kBlue), v = series("FOV vertical", Style::Line, kOrange),
             e = series("mean efficiency", Style::Dashed, kGreen, true),
             un = series("efficiency uniformity", Style::Dashed, kPurple, true);
  p.columns = {param,
               withUnit("FOV horizontal", u.angleSymbol()),
               withUnit("FOV vertical", u.angleSymbol()),
               withUnit("FOV diagonal", u.angleSymbol()),
               "mean efficiency",
               "efficiency uniformity",
               "rays in pupil"};
  for (const auto& s : arr(r, "samples")) {
    const double x = jsonNumber(s, {"value"});
    const double fh = u.angleFromDeg(jsonNumber(s, {"fov_deg", "horizontal"})),
                 fv = u.angleFromDeg(jsonNumber(s, {"fov_deg", "vertical"}));
    addPoint(h, x, fh);
    addPoint(v, x, fv);
    addPoint(e, x, jsonNumber(s, {"mean_efficiency"}));
    addPoint(un, x, jsonNumber(s, {"efficiency_uniformity"}));
    p.rows.append({cell(x), cell(fh), cell(fv), cell(u.angleFromDeg(jsonNumber(s, {"fov_deg", "diagonal"}))),
                   cell(jsonNumber(s, {"mean_efficiency"})), cell(jsonNumber(s, {"efficiency_uniformity"})),
                   cell(jsonNumber(s, {"rays_in_pupil"}))});
  }
  p.series = {h, v, e, un};
  p.caption = QString(
                  "Sensitivity of the retinal FOV (left axis), the mean efficiency and its uniformity (right "
                  "axis) to %1 (nominal %2), at the scene's gaze.")
                  .arg(param, fmt(jsonNumber(r, {"nominal_value"}), 5));
  p.source = source;
  return {p};
}

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

// ---- tolerance ----------------------------------------------------------------------------
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
  for (const QVariantList& row : p.rows)
    html += QString(
                "<tr><td align='right'>%1</td><td>%2</td><td align='right'>%3 ± %4</td>"
                "<td align='right'>%5 ± %6</td></tr>")
                .arg(row[0].toString(), row[1].toString().toHtmlEscaped(), fmt(row[2].toDouble(), 2),
                     fmt(row[3].toDouble(), 2), fmt(row[4].toDouble(), 2), fmt(row[5].toDouble(), 2));
  p.summaryHtml = html + "</table>";
  p.caption = QString(
                  "Which tolerance drives %1: total (Jansen 1999) and first-order (Saltelli et al. 2010) "
                  "variance-based indices of each parameter from the Saltelli design (%2 base samples), with "
                  "bootstrap standard errors (%3 resamples); ranked by the total index (tolerance).")
                  .arg(by.isEmpty() ? QString("failure") : by, fmt(jsonNumber(sens, {"base_samples"}), 6),
                       fmt(jsonNumber(sens, {"bootstrap_resamples"}), 6));
  p.source = source;
  return p;
}

QList<PlotData> fromTolerance(const nlohmann::json& r, const DisplayUnits& u, const QString& source) {
  QList<PlotData> out{yieldPlot(r, source), rankingPlot(r, source)};
  for (const ToleranceFigure& f : kToleranceFigures) out << histogramPlot(r, f, u, source);
  return out;
}

// ---- fit ----------------------------------------------------------------------------------
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
  int k = 0;
  for (const auto& t : arr(r, "targets")) {
    ++k;
    const double s = jsonNumber(t, {"sigma"}), v = jsonNumber(t, {"value"}), m0 = jsonNumber(t, {"initial_model"});
    const double n0 = (m0 - v) / s, n1 = jsonNumber(t, {"normalised"});
    addPoint(before, k, n0);
    addPoint(after, k, n1);
    p.rows.append({cell(k), str(t, "id"), str(t, "observable"), str(t, "unit"), cell(v), cell(s), cell(m0),
                   cell(jsonNumber(t, {"model"})), cell(n0), cell(n1), str(t, "source")});
  }
  plus.points = {QPointF(0.5, 1), QPointF(k + 0.5, 1)};
  minus.points = {QPointF(0.5, -1), QPointF(k + 0.5, -1)};
  p.x.min = 0.5;
  p.x.max = k + 0.5;
  p.series = {before, after, plus, minus};
  QString html =
      "<table border='1' cellspacing='0' cellpadding='3'><tr><th>parameter</th><th>start</th><th>fitted</th>"
      "<th>± σ</th><th>bounds</th><th>note</th></tr>";
  for (const auto& q : arr(r, "parameters")) {
    QString note;
    for (const auto& w : arr(r, "warnings"))
      if (w.value("parameter", std::string()) == q.value("path", std::string()))
        note += QString::fromStdString(w.value("message", std::string())).toHtmlEscaped();
    const double sigma = jsonNumber(q, {"uncertainty"});
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
                  "fit; χ² %1 → %2 (%3 degrees of freedom, %4 evaluations, %5).")
                  .arg(fmt(jsonNumber(r, {"chi2_initial"})), fmt(jsonNumber(r, {"chi2"})), fmt(jsonNumber(r, {"dof"})),
                       fmt(jsonNumber(r, {"evaluations"})), str(r, "algorithm"));
  p.source = source;
  return {p};
}

}  // namespace

QStringList plotIds() {
  return {"fov-vs-gaze",
          "travel-vs-gaze",
          "efficiency-vs-angle",
          "efficiency-vs-wavelength",
          "resolution-vs-eccentricity",
          "time-vs-error",
          "sensitivity",
          "lens-candidates",
          "tolerance-yield",
          "tolerance-ranking",
          "tolerance-fov_min_deg",
          "tolerance-fov_zero_gaze_deg",
          "tolerance-eyebox_mm",
          "tolerance-inset_error_deg",
          "tolerance-mean_efficiency",
          "fit-residuals"};
}

QString plotTitle(const QString& id) {
  static const QMap<QString, QString> titles{{"fov-vs-gaze", "FOV vs gaze"},
                                             {"travel-vs-gaze", "HOE travel vs gaze"},
                                             {"efficiency-vs-angle", "Efficiency vs detuning"},
                                             {"efficiency-vs-wavelength", "Efficiency vs wavelength"},
                                             {"resolution-vs-eccentricity", "Resolution vs eccentricity"},
                                             {"time-vs-error", "Kogelnik vs RCWA: error and time"},
                                             {"sensitivity", "Sensitivity"},
                                             {"lens-candidates", "Beam-shaping lens candidates"},
                                             {"tolerance-yield", "Tolerance: yield"},
                                             {"tolerance-ranking", "Tolerance: sensitivity ranking"},
                                             {"tolerance-fov_min_deg", "Tolerance: smallest FOV"},
                                             {"tolerance-fov_zero_gaze_deg", "Tolerance: FOV at zero gaze"},
                                             {"tolerance-eyebox_mm", "Tolerance: eye box"},
                                             {"tolerance-inset_error_deg", "Tolerance: inset error"},
                                             {"tolerance-mean_efficiency", "Tolerance: mean efficiency"},
                                             {"fit-residuals", "Fit residuals"}};
  return titles.value(id, id);
}

QStringList plotSources(const QString& id) {
  if (id == "fov-vs-gaze" || id == "travel-vs-gaze") return {"sweep"};
  if (id == "efficiency-vs-angle") return {"selectivity", "grating"};
  if (id == "efficiency-vs-wavelength") return {"selectivity"};
  if (id == "resolution-vs-eccentricity") return {"resolution"};
  if (id == "time-vs-error") return {"kogelnik-vs-rcwa"};
  if (id == "sensitivity") return {"sensitivity"};
  if (id == "lens-candidates") return {"optimize-lens"};
  if (id.startsWith("tolerance-")) return {"tolerance"};
  if (id == "fit-residuals") return {"fit"};
  return {};
}

QList<PlotData> plotsFromResult(const QString& id, const nlohmann::json& r, const DisplayUnits& u,
                                const QString& source) {
  if (!r.is_object()) return {};
  if (id == "sweep") return fromSweep(r, u, source);
  if (id == "selectivity") return fromSelectivity(r, u, source);
  if (id == "grating") return fromGrating(r, u, source);
  if (id == "resolution") return fromResolution(r, u, source);
  if (id == "kogelnik-vs-rcwa") return fromKogelnikVsRcwa(r, u, source);
  if (id == "sensitivity") return fromSensitivity(r, u, source);
  if (id == "optimize-lens") return fromLens(r, u, source);
  if (id == "tolerance") return fromTolerance(r, u, source);
  if (id == "fit") return fromFit(r, source);
  return {};
}

PlotData retinaMapPlot(const TraceResult& trace, double threshold, const DisplayUnits& u) {
  PlotData p;
  p.id = "retina-map";
  p.title = QString("Retina map at gaze (%1, %2) %3")
                .arg(fmt(u.angleFromDeg(trace.gaze_deg[0])), fmt(u.angleFromDeg(trace.gaze_deg[1])), u.angleSymbol());
  p.x.title = withUnit("visual angle, yaw", u.angleSymbol());
  p.y.title = withUnit("visual angle, pitch", u.angleSymbol());
  struct Bin {
    double lo, hi;
    QColor color;
  };
  const Bin bins[] = {{0.0, threshold, QColor(175, 175, 175)}, {threshold, 0.3, QColor(68, 1, 84)},
                      {0.3, 0.5, QColor(59, 82, 139)},         {0.5, 0.7, QColor(33, 145, 140)},
                      {0.7, 0.85, QColor(94, 201, 98)},        {0.85, 1.0 + 1e-9, QColor(253, 200, 37)}};
  QVector<PlotSeries> classes;
  for (const Bin& b : bins) {
    PlotSeries s = series(b.lo == 0.0 ? QString("η < %1").arg(fmt(threshold, 2))
                                      : QString("η %1–%2").arg(fmt(b.lo, 2), fmt(std::min(1.0, b.hi), 2)),
                          Style::Scatter, b.color);
    s.markerSize = 4.0;
    classes << s;
  }
  p.columns = {withUnit("yaw", u.angleSymbol()),
               withUnit("pitch", u.angleSymbol()),
               "wavelength (nm)",
               "efficiency",
               "pixel x",
               "pixel y"};
  double ymin = INFINITY, ymax = -INFINITY, pmin = INFINITY, pmax = -INFINITY;
  for (const TracedRay& r : trace.ray_list) {
    if (!r.in_pupil) continue;
    const double y = u.angleFromDeg(r.field_deg[0]), pt = u.angleFromDeg(r.field_deg[1]);
    for (int b = 0; b < 6; ++b)
      if (r.efficiency >= bins[b].lo && r.efficiency < bins[b].hi) {
        addPoint(classes[b], y, pt);
        break;
      }
    if (r.efficiency >= threshold) {
      ymin = std::min(ymin, y), ymax = std::max(ymax, y);
      pmin = std::min(pmin, pt), pmax = std::max(pmax, pt);
    }
    p.rows.append(
        {cell(y), cell(pt), cell(r.wavelength_nm), cell(r.efficiency), QVariant(r.pixel[0]), QVariant(r.pixel[1])});
  }
  for (const PlotSeries& s : classes)
    if (!s.points.isEmpty()) p.series << s;
  if (ymin < ymax) {
    PlotSeries box = series("FOV box", Style::Dashed, QColor(20, 20, 20));
    box.points = {QPointF(ymin, pmin), QPointF(ymax, pmin), QPointF(ymax, pmax), QPointF(ymin, pmax),
                  QPointF(ymin, pmin)};
    p.series << box;
  }
  p.caption = QString(
                  "Retina map at gaze (%1, %2) %3: the visual angle of every projector ray entering the pupil "
                  "(all wavelengths), coloured by diffraction efficiency; the dashed box is the FOV of the rays "
                  "with η ≥ %4: %5 × %6 %3 (diagonal %7 %3), mean efficiency %8.")
                  .arg(fmt(u.angleFromDeg(trace.gaze_deg[0])), fmt(u.angleFromDeg(trace.gaze_deg[1])), u.angleSymbol(),
                       fmt(threshold, 2), fmt(u.angleFromDeg(trace.fov_deg.horizontal)),
                       fmt(u.angleFromDeg(trace.fov_deg.vertical)), fmt(u.angleFromDeg(trace.fov_deg.diagonal)),
                       fmt(trace.mean_efficiency, 3));
  return p;
}

}  // namespace fovea::widgets

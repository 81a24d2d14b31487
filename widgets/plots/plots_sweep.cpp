// Plots of the FOV analyses: sweep (FOV and HOE travel vs gaze) and sensitivity.
#include <QColor>

#include <algorithm>
#include <cmath>

#include "model/json_numbers.h"
#include "widgets/plots/plot_builders.h"
#include "widgets/plots/plot_helpers.h"

namespace fovea::widgets::plots {

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

}  // namespace fovea::widgets::plots

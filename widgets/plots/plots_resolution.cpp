// Plot of the resolution analysis: resolution vs eccentricity.
#include <QColor>

#include <algorithm>
#include <cmath>

#include "model/json_numbers.h"
#include "widgets/plots/plot_builders.h"
#include "widgets/plots/plot_helpers.h"

namespace fovea::widgets::plots {

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
  if (r.contains("accommodation") && r["accommodation"].is_object())
    return {p, fromResolutionAccommodation(r["accommodation"], source)};
  return {p};
}

}  // namespace fovea::widgets::plots

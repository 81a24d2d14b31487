// Plot of the resolution analysis' accommodation sweep (--accommodation-d, issue 29):
// peripheral and foveal cpd (MTF50, MTF10 of the retinal PSFs) against accommodation.
#include <QColor>

#include <algorithm>
#include <cmath>

#include "model/json_numbers.h"
#include "widgets/plots/plot_builders.h"
#include "widgets/plots/plot_helpers.h"

namespace fovea::widgets::plots {

namespace {
// The seed's peripheral resolution (C.3): "3 cpd", all-in-focus.
constexpr double kSeedPeripheralCpd = 3.0;
}  // namespace

PlotData fromResolutionAccommodation(const nlohmann::json& a, const QString& source) {
  PlotData p;
  p.id = "resolution-vs-accommodation";
  p.title = plotTitle(p.id);
  p.x.title = "accommodation (D)";
  p.y.title = "resolution (cycles per degree)";
  p.y.log = true;
  PlotSeries f50 = series("foveal MTF50", Style::Line, kBlue), f10 = series("foveal MTF10", Style::Dashed, kBlue),
             p50 = series("peripheral MTF50", Style::Line, kOrange),
             p10 = series("peripheral MTF10", Style::Dashed, kOrange),
             seed = series("seed: peripheral 3 cpd (C.3)", Style::Dashed, kGray);
  p.columns = {"accommodation (D)",        "distance (cm)",      "peripheral MTF50 (cpd)", "peripheral MTF10 (cpd)",
               "peripheral spot (arcmin)", "foveal MTF50 (cpd)", "foveal MTF10 (cpd)",     "foveal spot (arcmin)",
               "foveal defocus (D)"};
  double xmin = INFINITY, xmax = -INFINITY;
  for (const auto& s : arr(a, "samples")) {
    const double d = jsonNumber(s, {"accommodation_d"});
    const double pm50 = jsonNumber(s, {"peripheral", "cpd_mtf50"}), pm10 = jsonNumber(s, {"peripheral", "cpd_mtf10"});
    const double fm50 = jsonNumber(s, {"foveal", "cpd_mtf50"}), fm10 = jsonNumber(s, {"foveal", "cpd_mtf10"});
    addPoint(p50, d, pm50);
    addPoint(p10, d, pm10);
    addPoint(f50, d, fm50);
    addPoint(f10, d, fm10);
    if (std::isfinite(d)) xmin = std::min(xmin, d), xmax = std::max(xmax, d);
    p.rows.append({cell(d), cell(jsonNumber(s, {"distance_cm"})), cell(pm50), cell(pm10),
                   cell(jsonNumber(s, {"peripheral", "spot_fwhm_arcmin"})), cell(fm50), cell(fm10),
                   cell(jsonNumber(s, {"foveal", "spot_fwhm_arcmin"})), cell(jsonNumber(s, {"foveal_defocus_d"}))});
  }
  if (xmin <= xmax)
    seed.points = {QPointF(xmin, kSeedPeripheralCpd), QPointF(xmax > xmin ? xmax : xmin + 1, kSeedPeripheralCpd)};
  seed.markerSize = 0;
  p.series = {f50, f10, p50, p10, seed};
  const double change = jsonNumber(a, {"peripheral_spot_change"});
  const auto g = a.contains("gaze_deg") ? a["gaze_deg"] : nlohmann::json::array();
  p.caption = QString(
                  "Resolution against accommodation at the line of sight, gaze (%1, %2) deg: cpd at MTF50 and "
                  "MTF10 of the retinal PSFs of the peripheral projector (pixel beam through the HOE and the "
                  "accommodating Navarro eye) and the foveal micro-OLED (defocused pupil, pixel, combiner). "
                  "The peripheral spot changes by %3 % over the range.")
                  .arg(g.size() == 2 ? fmt(g[0].get<double>()) : "—")
                  .arg(g.size() == 2 ? fmt(g[1].get<double>()) : "—")
                  .arg(std::isfinite(change) ? fmt(100.0 * change, 3) : "—");
  p.source = source;
  return p;
}

}  // namespace fovea::widgets::plots

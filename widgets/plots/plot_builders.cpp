#include "widgets/plots/plot_builders.h"

// The plot registry: ids, titles, the analyses that fill each plot, and the dispatch to the
// builder of each family (plots_<family>.cpp).

#include <QMap>

#include "widgets/plots/plot_helpers.h"

namespace fovea::widgets {

QStringList plotIds() {
  return {"fov-vs-gaze",
          "travel-vs-gaze",
          "efficiency-vs-angle",
          "efficiency-vs-wavelength",
          "resolution-vs-eccentricity",
          "resolution-vs-accommodation",
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
                                             {"resolution-vs-accommodation", "Resolution vs accommodation"},
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
  if (id == "resolution-vs-eccentricity" || id == "resolution-vs-accommodation") return {"resolution"};
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
  if (id == "sweep") return plots::fromSweep(r, u, source);
  if (id == "selectivity") return plots::fromSelectivity(r, u, source);
  if (id == "grating") return plots::fromGrating(r, u, source);
  if (id == "resolution") return plots::fromResolution(r, u, source);
  if (id == "kogelnik-vs-rcwa") return plots::fromKogelnikVsRcwa(r, u, source);
  if (id == "sensitivity") return plots::fromSensitivity(r, u, source);
  if (id == "optimize-lens") return plots::fromLens(r, u, source);
  if (id == "tolerance") return plots::fromTolerance(r, u, source);
  if (id == "fit") return plots::fromFit(r, source);
  return {};
}

}  // namespace fovea::widgets

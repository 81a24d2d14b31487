#include "widgets/analyses/analysis_summary.h"

#include <QStringList>

#include <cmath>

#include "model/json_numbers.h"
#include "widgets/number_text.h"

namespace fovea::widgets {

namespace {

QString g(double v, int significant = 4) {
  return numberText(v, significant);
}
QString pct(double v) {
  return percentText(v);
}

struct Table {
  QStringList rows;
  void add(const QString& k, const QString& v) { rows << "<tr><td>" + k + "</td><td><b>" + v + "</b></td></tr>"; }
  QString html() const { return "<table cellspacing='0' cellpadding='2'>" + rows.join("") + "</table>"; }
};

QString fovText(const nlohmann::json& f, const DisplayUnits& u) {
  return QString("%1 × %2 %3 (diagonal %4)")
      .arg(g(u.angleFromDeg(jsonNumber(f, {"horizontal"}))), g(u.angleFromDeg(jsonNumber(f, {"vertical"}))),
           u.angleSymbol(), g(u.angleFromDeg(jsonNumber(f, {"diagonal"}))));
}

QString range(const nlohmann::json& j, const char* key, bool length, const DisplayUnits& u) {
  const double a = jsonNumberAt(j, key, 0), b = jsonNumberAt(j, key, 1);
  if (length) return g(u.lengthFromMm(a)) + " … " + g(u.lengthFromMm(b)) + " " + u.lengthSymbol();
  return g(u.angleFromDeg(a)) + " … " + g(u.angleFromDeg(b)) + " " + u.angleSymbol();
}

}  // namespace

QString toleranceIntervalBasis(const nlohmann::json& y) {
  if (y.is_object() && y.contains("interval_basis") && y["interval_basis"].is_string())
    return QString::fromStdString(y["interval_basis"].get<std::string>()).toHtmlEscaped();
  return QString("%1 independent samples").arg(g(jsonNumber(y, {"independent_samples"}), 8));
}

QString analysisSummaryHtml(const QString& id, const nlohmann::json& r, const DisplayUnits& u) {
  if (!r.is_object()) return {};
  Table t;
  QString extra;
  if (id == "trace") {
    t.add("Retinal FOV", fovText(r.value("fov_deg", nlohmann::json::object()), u));
    t.add("Gaze", range(r, "gaze_deg", false, u).replace(" … ", ", "));
    t.add("Rays in the pupil / efficient / traced",
          QString("%1 / %2 / %3")
              .arg(g(jsonNumber(r, {"rays_in_pupil"}), 8), g(jsonNumber(r, {"rays_efficient"}), 8),
                   g(jsonNumber(r, {"rays"}), 8)));
    t.add("Mean efficiency in the pupil", pct(jsonNumber(r, {"mean_efficiency"})));
    t.add("Mean efficiency on the HOE", pct(jsonNumber(r, {"mean_efficiency_on_hoe"})));
    if (r.contains("per_wavelength"))
      for (const auto& w : r["per_wavelength"])
        t.add(QString("%1 nm").arg(g(jsonNumber(w, {"wavelength_nm"}))),
              fovText(w.value("fov_deg", nlohmann::json::object()), u) + ", η " +
                  pct(jsonNumber(w, {"mean_efficiency"})));
  } else if (id == "sweep") {
    const auto& eb = r.value("eyebox", nlohmann::json::object());
    t.add("Eye box", u.length(jsonNumber(r, {"eyebox_mm"})));
    t.add("Gaze range of the eye box", range(eb, "gaze_range_deg", false, u));
    t.add("Pupil range", range(eb, "pupil_range_mm", true, u));
    t.add("HOE travel at the borders", range(eb, "travel_mm", true, u));
    t.add("Zero-gaze FOV (reference)", u.angle(jsonNumber(eb, {"reference_fov_deg"})));
    if (eb.value("lower_border_found", true) == false || eb.value("upper_border_found", true) == false)
      extra = "<p><i>A border of the eye box lies outside the studied gaze range: the width is a lower bound.</i></p>";
  } else if (id == "compare-shift") {
    for (const char* k : {"hoe_shift", "source_shift"}) {
      const auto& m = r.value(k, nlohmann::json::object());
      t.add(QString(k) == "hoe_shift" ? "Moving the HOE" : "Moving the point source",
            QString("eye box %1, gaze %2, travel %3")
                .arg(u.length(jsonNumber(m, {"eyebox_mm"})), range(m, "gaze_range_deg", false, u),
                     range(m, "travel_mm", true, u)));
    }
    t.add("Eye-box ratio (HOE / source)", g(jsonNumber(r, {"eyebox_ratio"})));
  } else if (id == "sensitivity") {
    t.add("Parameter", QString::fromStdString(r.value("parameter", std::string())));
    t.add("Nominal value", g(jsonNumber(r, {"nominal_value"}), 6));
    double fmin = INFINITY, fmax = -INFINITY, emin = INFINITY, emax = -INFINITY;
    for (const auto& s : r.value("samples", nlohmann::json::array())) {
      const double f = jsonNumber(s, {"fov_deg", "horizontal"}), e = jsonNumber(s, {"mean_efficiency"});
      if (std::isfinite(f)) fmin = std::min(fmin, f), fmax = std::max(fmax, f);
      if (std::isfinite(e)) emin = std::min(emin, e), emax = std::max(emax, e);
    }
    t.add("Horizontal FOV over the range",
          g(u.angleFromDeg(fmin)) + " … " + g(u.angleFromDeg(fmax)) + " " + u.angleSymbol());
    t.add("Mean efficiency over the range", pct(emin) + " … " + pct(emax));
  } else if (id == "resolution") {
    t.add("Peripheral field", range(r, "peripheral_field_deg", false, u));
    t.add("Foveal field", range(r, "foveal_field_deg", false, u));
    t.add("Peripheral pixels along the gaze row",
          g(jsonNumber(r, {"peripheral_pixel_integral"})) + " of " + g(jsonNumber(r, {"pixels_horizontal"}), 6));
    t.add("Projector pixels per degree", g(jsonNumber(r, {"projector_pixels_per_deg"})));
    double best = NAN, nearest = INFINITY;
    for (const auto& s : r.value("samples", nlohmann::json::array())) {
      const double e = std::abs(jsonNumber(s, {"eccentricity_deg"}));
      if (e < nearest) nearest = e, best = jsonNumber(s, {"perceived_cpd"});
    }
    t.add("Perceived resolution at the gaze", g(best) + " cpd");
  } else if (id == "optimize-lens") {
    t.add("Best lens", QString::fromStdString(r.value("vendor", std::string()) + " " + r.value("part", std::string())) +
                           QString(" (f = %1)").arg(u.length(jsonNumber(r, {"focal_length_mm"}))));
    t.add("Distance / decentre / tilt",
          QString("%1 / %2 / %3")
              .arg(u.length(jsonNumber(r, {"distance_mm"})), u.length(jsonNumber(r, {"decenter_mm"})),
                   u.angle(jsonNumber(r, {"tilt_deg"}))));
    t.add("RMS spot on the HOE",
          QString("%1 µm → %2 µm (%3 % sharper)")
              .arg(g(jsonNumber(r, {"rms_spot_um", "before"})), g(jsonNumber(r, {"rms_spot_um", "after"})),
                   g(jsonNumber(r, {"improvement_percent"}), 3)));
  } else if (id == "selectivity") {
    for (const auto& l : r.value("layers", nlohmann::json::array()))
      t.add(QString::fromStdString(l.value("name", std::string())) +
                QString(" (%1 nm)").arg(g(jsonNumber(l, {"probe_wavelength_nm"}))),
            QString("η %1 nominal, peak %2 at %3; FWHM %4, %5 nm")
                .arg(pct(jsonNumber(l, {"nominal_efficiency"})), pct(jsonNumber(l, {"peak_angle_efficiency"})),
                     u.angle(jsonNumber(l, {"peak_detuning_deg"}), 3), u.angle(jsonNumber(l, {"angular_fwhm_deg"}), 3),
                     g(jsonNumber(l, {"spectral_fwhm_nm"}), 3)));
  } else if (id == "grating") {
    const auto& c = r.value("center", nlohmann::json::object());
    t.add("Type", QString::fromStdString(c.value("type", std::string())));
    t.add("Efficiency at the probe", g(jsonNumber(c, {"efficiency"}), 5));
    t.add("ν, ξ", g(jsonNumber(c, {"nu"})) + ", " + g(jsonNumber(c, {"xi"})));
  } else if (id == "kogelnik-vs-rcwa") {
    const auto& pts = r.value("points", nlohmann::json::array());
    double worst = 0, sk = 0, sr = 0;
    for (const auto& p : pts) {
      worst = std::max(worst, jsonNumber(p, {"abs_error"}));
      sk += jsonNumber(p, {"kogelnik_ns"});
      sr += jsonNumber(p, {"rcwa_ms"});
    }
    t.add("Grid points", g(double(pts.size()), 6));
    t.add("Largest |Δη|", QString::number(worst, 'e', 2));
    if (!pts.empty()) {
      t.add("Mean Kogelnik time", g(sk / pts.size(), 3) + " ns");
      t.add("Mean converged RCWA time", g(sr / pts.size(), 3) + " ms");
    }
  } else if (id == "tolerance") {
    const auto& y = r.value("yield", nlohmann::json::object());
    // The interval's basis beside the number: with the Saltelli design it rests on far fewer
    // independent samples than units (model/analysis/tolerance_stats.cpp).
    t.add("Yield", QString("%1 (95 % interval %2 – %3 over %4; %5 of %6 units pass)")
                       .arg(pct(jsonNumber(y, {"value"})), pct(jsonNumberAt(y, "confidence_95", 0)),
                            pct(jsonNumberAt(y, "confidence_95", 1)), toleranceIntervalBasis(y),
                            g(jsonNumber(y, {"passed"}), 8), g(jsonNumber(y, {"trials"}), 8)));
    t.add("Target yield", pct(jsonNumber(r, {"spec", "target_yield"})));
    const auto& f = r.value("figures", nlohmann::json::object());
    t.add("Smallest FOV over the gazes",
          QString("%1 ± %2 (nominal %3)")
              .arg(u.angle(jsonNumber(f, {"fov_min_deg", "mean"})), u.angle(jsonNumber(f, {"fov_min_deg", "std"})),
                   u.angle(jsonNumber(r, {"nominal", "fov_min_deg"}))));
    t.add("Eye box",
          QString("%1 ± %2 (nominal %3)")
              .arg(u.length(jsonNumber(f, {"eyebox_mm", "mean"})), u.length(jsonNumber(f, {"eyebox_mm", "std"})),
                   u.length(jsonNumber(r, {"nominal", "eyebox_mm"}))));
    const auto& s = r.value("sensitivity", nlohmann::json::object());
    QStringList top;
    for (const auto& p : s.value("ranking", nlohmann::json::array()))
      if (top.size() < 3 && p.is_string()) top << QString::fromStdString(p.get<std::string>());
    if (!top.isEmpty())
      t.add("Drives " + QString::fromStdString(s.value("ranked_by", std::string("failure"))), top.join(", "));
    if (jsonNumber(y, {"invalid_units"}) > 0)
      extra = QString("<p><i>%1 units broke the scene rules and count as failed.</i></p>")
                  .arg(g(jsonNumber(y, {"invalid_units"}), 8));
  } else if (id == "fit") {
    t.add("χ² before → after", g(jsonNumber(r, {"chi2_initial"})) + " → " + g(jsonNumber(r, {"chi2"})) +
                                   QString(" (%1 dof)").arg(g(jsonNumber(r, {"dof"}))));
    const double reduced = jsonNumber(r, {"reduced_chi2"});
    // chi2/dof > 1: the scaled uncertainties (sigma * sqrt(chi2/dof)) are shown, and said so.
    const bool scaled = r.value("uncertainties_shown", std::string()) == "scaled";
    t.add("Reduced χ² (χ²/dof)", std::isfinite(reduced) ? g(reduced, 3) + (reduced > 1 ? " > 1" : "")
                                                        : QStringLiteral("— (no degree of freedom)"));
    if (const auto sel = r.value("targets_select", std::string()); !sel.empty())
      t.add("Targets used",
            QString("%1 of %2 (%3)")
                .arg(r.value("targets", nlohmann::json::array()).size())
                .arg(g(jsonNumber(r, {"targets_available"}), 6), QString::fromStdString(sel).toHtmlEscaped()));
    for (const auto& p : r.value("parameters", nlohmann::json::array())) {
      const double sigma = jsonNumber(p, {scaled ? "uncertainty_scaled" : "uncertainty"});
      const double raw = jsonNumber(p, {"uncertainty"});
      t.add(QString::fromStdString(p.value("path", std::string())),
            QString("%1 ± %2 %3 (was %4)%5")
                .arg(g(jsonNumber(p, {"fitted"}), 6), std::isfinite(sigma) ? g(sigma, 3) : QStringLiteral("?"),
                     QString::fromStdString(p.value("unit", std::string())), g(jsonNumber(p, {"initial"}), 6),
                     scaled && std::isfinite(raw)
                         ? QString("; scaled by √(χ²/dof), from the targets' σ alone ± %1").arg(g(raw, 3))
                         : QString()));
    }
    for (const auto& w : r.value("warnings", nlohmann::json::array())) {
      const bool whole = w.value("parameter", std::string()).empty();
      extra += QString(whole ? "<p style='color:#b71c1c'><b>" : "<p><i>") +
               QString::fromStdString((whole ? std::string() : w.value("parameter", std::string()) + ": ") +
                                      w.value("message", std::string()))
                   .toHtmlEscaped() +
               (whole ? "</b></p>" : "</i></p>");
    }
  } else {
    return {};
  }
  if (r.value("cached", false)) extra += "<p><i>From the study cache (same scene and parameters).</i></p>";
  return t.html() + extra;
}

}  // namespace fovea::widgets

#include "app/studio/report_data.h"

#include <QRegularExpression>

#include <algorithm>
#include <cmath>

#include "model/analysis/hoe_travel.h"
#include "model/physics/projector_rays.h"
#include "widgets/analyses/analysis_catalog.h"

namespace fovea::studio {

using widgets::AnalysisParams;
using widgets::defaultParameters;
using widgets::findAnalysis;
using widgets::runAnalysis;

bool parseGaze(const QString& text, std::array<double, 2>* gaze) {
  const QStringList parts = text.trimmed().split(',');
  if (parts.isEmpty() || parts.size() > 2) return false;
  std::array<double, 2> g{0, 0};
  for (int i = 0; i < parts.size(); ++i) {
    bool ok = false;
    g[i] = parts[i].trimmed().toDouble(&ok);
    if (!ok || !std::isfinite(g[i]) || std::abs(g[i]) > 90) return false;
  }
  *gaze = g;
  return true;
}

namespace {

// Runs one catalogue analysis as part of the report: progress mapped into [from, to).
std::optional<nlohmann::json> step(const QString& id, const Scene& scene, AnalysisParams params,
                                   const StudyControl& control, double from, double to, QStringList& problems,
                                   bool* cancelled) {
  StudyControl sub;
  sub.cancel = control.cancel;
  if (control.on_progress) sub.on_progress = [&](double f) { control.on_progress(from + (to - from) * f); };
  try {
    auto r = runAnalysis(id, scene, params, sub);
    if (!r) *cancelled = true;
    return r;
  } catch (const std::exception& e) {
    problems << QString("%1: %2").arg(id, QString::fromUtf8(e.what()));
    return std::nullopt;
  }
}

}  // namespace

std::optional<ReportData> computeReportData(const Scene& scene, const QString& scenePath, ReportOptions options,
                                            const StudyControl& outer) {
  // With the tolerance analysis the other analyses take the first 60 % of the progress.
  const double share = options.tolerance ? 0.6 : 1.0;
  StudyControl control;
  control.cancel = outer.cancel;
  if (outer.on_progress) control.on_progress = [&outer, share](double f) { outer.on_progress(share * f); };
  ReportData d;
  d.scene = scene;
  d.scenePath = scenePath;
  if (options.gazes_deg.isEmpty()) options.gazes_deg = {scene.eye.gaze_deg};
  d.options = options;
  bool cancelled = false;
  auto progress = [&](double f) {
    if (control.on_progress) control.on_progress(std::min(1.0, f));
  };

  // Traces at the chosen gazes (20 %).
  const int n = static_cast<int>(options.gazes_deg.size());
  for (int i = 0; i < n; ++i) {
    if (control.cancelled()) return std::nullopt;
    GazeTrace t;
    t.gaze_deg = options.gazes_deg[i];
    if (options.follow_gaze) {
      // The one x_p source (hoe_travel.h), as the live trace, the capture plan and the bench.
      try {
        t.hoe_shift_mm = hoeTravel(scene, t.gaze_deg, sceneXpRule(scene)).shift_mm;
      } catch (const std::exception& e) {
        d.problems << QString("HOE shift at gaze %1,%2: %3").arg(t.gaze_deg[0]).arg(t.gaze_deg[1]).arg(e.what());
        t.hoe_shift_mm = {0, 0};
      }
    }
    AnalysisParams p = defaultParameters(*findAnalysis("trace"), options.rays);
    p["gaze-yaw"] = t.gaze_deg[0];
    p["gaze-pitch"] = t.gaze_deg[1];
    p["hoe-shift-x"] = t.hoe_shift_mm[0];
    p["hoe-shift-y"] = t.hoe_shift_mm[1];
    auto j = step("trace", scene, p, control, 0.2 * i / n, 0.2 * (i + 0.5) / n, d.problems, &cancelled);
    if (cancelled) return std::nullopt;
    if (!j) continue;
    t.json = *j;
    TraceOptions o;
    o.gaze_deg = t.gaze_deg;
    o.rays = options.rays;
    o.hoe_shift_mm = t.hoe_shift_mm;
    o.keep_rays = true;
    t.rays = traceScene(scene, o);
    t.grid = projectorGrid(scene.projector, o.rays);
    d.traces << t;
    progress(0.2 * (i + 1) / n);
  }

  // Gaze sweep over the scene's design gaze range (40 %).
  AnalysisParams sweep = defaultParameters(*findAnalysis("sweep"), options.rays);
  double lo = std::min(scene.eye.gaze_range_deg[0], scene.eye.gaze_range_deg[1]);
  double hi = std::max(scene.eye.gaze_range_deg[0], scene.eye.gaze_range_deg[1]);
  if (!(hi > lo)) lo = -20, hi = 20;
  sweep["gaze-from"] = lo;
  sweep["gaze-to"] = hi;
  sweep["gaze-step"] = std::max(0.5, options.sweep_step_deg);
  if (auto j = step("sweep", scene, sweep, control, 0.2, 0.6, d.problems, &cancelled)) d.sweep = *j;
  if (cancelled) return std::nullopt;

  // Resolution at the first gaze (10 %), selectivity (5 %).
  AnalysisParams res = defaultParameters(*findAnalysis("resolution"));
  res["gaze-yaw"] = options.gazes_deg.front()[0];
  res["gaze-pitch"] = options.gazes_deg.front()[1];
  if (auto j = step("resolution", scene, res, control, 0.6, 0.7, d.problems, &cancelled)) d.resolution = *j;
  if (cancelled) return std::nullopt;
  if (!scene.hoe_layers.empty()) {
    if (auto j = step("selectivity", scene, defaultParameters(*findAnalysis("selectivity")), control, 0.7, 0.75,
                      d.problems, &cancelled))
      d.selectivity = *j;
    if (cancelled) return std::nullopt;
  }

  // Kogelnik vs RCWA (quick grid, scene-independent) (25 %).
  if (options.kogelnik_vs_rcwa) {
    if (auto j = step("kogelnik-vs-rcwa", scene, defaultParameters(*findAnalysis("kogelnik-vs-rcwa")), control, 0.75,
                      1.0, d.problems, &cancelled))
      d.kogelnikVsRcwa = *j;
    if (cancelled) return std::nullopt;
  }
  progress(1.0);

  // Tolerance (the remaining 40 %).
  if (options.tolerance) {
    AnalysisParams tol = defaultParameters(*findAnalysis("tolerance"));
    if (!options.tolerance_spec.isEmpty()) tol["spec"] = options.tolerance_spec;
    tol["trials"] = options.tolerance_trials;
    tol["seed"] = options.tolerance_seed;
    if (auto j = step("tolerance", scene, tol, outer, share, 1.0, d.problems, &cancelled)) d.tolerance = *j;
    if (cancelled) return std::nullopt;
    if (outer.on_progress) outer.on_progress(1.0);
  }
  return d;
}

}  // namespace fovea::studio

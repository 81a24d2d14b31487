#include "model/analysis/tolerance_trial.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "model/analysis/trace_evaluator.h"
#include "model/scene/scene_parameters.h"

namespace fovea {

double CompensationTable::at(double gaze_deg) const {
  if (gazes_deg.empty()) return 0.0;
  if (gaze_deg <= gazes_deg.front()) return shifts_mm.front();
  if (gaze_deg >= gazes_deg.back()) return shifts_mm.back();
  const auto it = std::upper_bound(gazes_deg.begin(), gazes_deg.end(), gaze_deg);
  const std::size_t k = static_cast<std::size_t>(it - gazes_deg.begin());
  const double t = (gaze_deg - gazes_deg[k - 1]) / (gazes_deg[k] - gazes_deg[k - 1]);
  return shifts_mm[k - 1] + t * (shifts_mm[k] - shifts_mm[k - 1]);
}

CompensationTable nominalCompensation(const Scene& nominal, const ToleranceSpec& spec, const FovEvaluator& eval) {
  const Scene scene = perturbedScene(nominal, spec, std::vector<double>(spec.parameters.size(), 0.0));
  CompensationTable t;
  t.gazes_deg = spec.gazes_deg;
  for (const double g : spec.gazes_deg)
    t.shifts_mm.push_back(spec.method == ShiftMethod::None
                              ? 0.0
                              : optimiseShift(scene, eval, g, spec.axis, spec.method, spec.optimiser).shift_mm);
  return t;
}

Scene perturbedScene(const Scene& scene, const ToleranceSpec& spec, const std::vector<double>& x) {
  Scene out = scene;
  for (std::size_t p = 0; p < spec.parameters.size(); ++p)
    if (spec.parameters[p].kind == ToleranceKind::Scene)
      out = withParameter(out, spec.parameters[p].path, parameterValue(out, spec.parameters[p].path) + x[p]);
  for (std::size_t p = 0; p < spec.parameters.size(); ++p) {
    const ToleranceParameter& t = spec.parameters[p];
    if (t.kind != ToleranceKind::LaserTemperature) continue;
    auto& w = out.projector.wavelengths_nm;
    if (t.drift_nm_per_K.size() != 1 && t.drift_nm_per_K.size() != w.size())
      throw std::invalid_argument("tolerance spec: " + t.name + ": drift_nm_per_K has " +
                                  std::to_string(t.drift_nm_per_K.size()) + " values for " + std::to_string(w.size()) +
                                  " lasers");
    for (std::size_t i = 0; i < w.size(); ++i)
      w[i] += (t.drift_nm_per_K.size() == 1 ? t.drift_nm_per_K[0] : t.drift_nm_per_K.at(i)) * x[p];
  }
  if (spec.wavelength_nm) {  // trace only that laser, at its drifted wavelength
    const auto& nominal = scene.projector.wavelengths_nm;
    std::size_t i = 0;
    while (i < nominal.size() && std::abs(nominal[i] - *spec.wavelength_nm) > 0.5) ++i;
    if (i == nominal.size())
      throw std::invalid_argument("tolerance spec: wavelength_nm: no projector laser at " +
                                  std::to_string(*spec.wavelength_nm) + " nm");
    out.projector.wavelengths_nm = {out.projector.wavelengths_nm[i]};
  }
  return out;
}

FovEvaluator toleranceEvaluator(const ToleranceSpec& spec) {
  TraceEvaluatorOptions o;
  o.fov_method = FovMethod::Edges;
  o.edge_tolerance_deg = spec.fov_tolerance_deg;
  return traceEvaluator(o);
}

namespace {

// Pupil position where the FOV crosses `level` between samples a (good) and b (bad).
double crossing(double fov_a, double fov_b, double pos_a, double pos_b, double level) {
  const double d = fov_a - fov_b;
  const double t = d > 0 ? std::clamp((fov_a - level) / d, 0.0, 1.0) : 0.0;
  return pos_a + t * (pos_b - pos_a);
}

}  // namespace

std::vector<double> runToleranceTrial(const Scene& nominal, const ToleranceSpec& spec, const FovEvaluator& eval,
                                      const std::vector<double>& x, const CompensationTable& table) {
  const Scene scene = perturbedScene(nominal, spec, x);
  double tracker = 0, repeat = 0, backlash = 0;
  for (std::size_t p = 0; p < spec.parameters.size(); ++p) {
    switch (spec.parameters[p].kind) {
      case ToleranceKind::GazeTracker:
        tracker += x[p];
        break;
      case ToleranceKind::StageRepeatability:
        repeat += x[p];
        break;
      case ToleranceKind::StageBacklash:
        backlash += std::abs(x[p]);
        break;
      default:
        break;
    }
  }
  const std::size_t n = spec.gazes_deg.size();
  std::vector<double> fov(n), pos(n);
  double efficiency = 0, previous = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double g = spec.gazes_deg[k], reported = g + tracker;
    double actual = 0;
    if (spec.method != ShiftMethod::None) {
      const double commanded =
          spec.compensator == Compensator::Fixed
              ? table.at(reported)
              : optimiseShift(scene, eval, reported, spec.axis, spec.method, spec.optimiser).shift_mm;
      const double direction = commanded > previous ? 1.0 : commanded < previous ? -1.0 : 0.0;
      actual = commanded + repeat - direction * 0.5 * backlash;
      previous = commanded;
    }
    const FovSample f = eval(scene, gazeQuery(g, spec.axis, spec.method, actual));
    fov[k] = axisFov(f, spec.axis);
    pos[k] = pupilPositionMm(scene, g, spec.axis);
    efficiency += f.mean_efficiency;
  }
  std::vector<double> out(toleranceFigureNames().size(), 0.0);
  if (n == 0) return out;
  std::size_t c = 0;
  for (std::size_t k = 1; k < n; ++k)
    if (std::abs(spec.gazes_deg[k]) < std::abs(spec.gazes_deg[c])) c = k;
  const double level = fov[c] - spec.eyebox_tolerance_deg;
  std::size_t hi = c, lo = c;
  while (hi + 1 < n && fov[hi + 1] >= level) ++hi;
  while (lo > 0 && fov[lo - 1] >= level) --lo;
  const double upper = hi + 1 < n ? crossing(fov[hi], fov[hi + 1], pos[hi], pos[hi + 1], level) : pos[hi];
  const double lower = lo > 0 ? crossing(fov[lo], fov[lo - 1], pos[lo], pos[lo - 1], level) : pos[lo];
  out[0] = *std::min_element(fov.begin(), fov.end());
  out[1] = fov[c];
  out[2] = std::abs(upper - lower);
  out[3] = std::abs(tracker);
  out[4] = efficiency / static_cast<double>(n);
  return out;
}

}  // namespace fovea

#include "model/analysis/gaze_studies.h"

#include "model/analysis/analysis_parameters.h"  // kMaxGazeSamples
#include "model/analysis/eyebox_walk.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

#include "model/scene/scene_geometry.h"
#include "model/scene/scene_io.h"

namespace fovea {

double axisFov(const FovSample& f, GazeAxis axis) {
  return axis == GazeAxis::Yaw ? f.horizontal_deg : f.vertical_deg;
}

double eyeBoxThresholdDeg(double reference_fov_deg, const GazeStudyOptions& options) {
  return reference_fov_deg -
         (options.criterion == EyeBoxCriterion::CentreFov ? kCentreFovSlackDeg : options.tolerance_deg);
}

Scene withSourceAlongAxis(const Scene& scene, double shift_mm) {
  Scene out = scene;
  const Eigen::Vector3d axis = rotationFromDeg(scene.projector.pose.rotation_deg) * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d p = toVec(scene.projector.pose.position_mm) + shift_mm * axis;
  out.projector.pose.position_mm = {p.x(), p.y(), p.z()};
  return out;
}

FovQuery gazeQuery(double gaze_deg, GazeAxis axis, ShiftMethod method, double shift_mm) {
  FovQuery q;
  q.gaze_deg = axis == GazeAxis::Yaw ? std::array<double, 2>{gaze_deg, 0.0} : std::array<double, 2>{0.0, gaze_deg};
  if (method == ShiftMethod::Hoe)
    q.hoe_shift_mm =
        axis == GazeAxis::Yaw ? std::array<double, 2>{shift_mm, 0.0} : std::array<double, 2>{0.0, shift_mm};
  else if (method == ShiftMethod::Source)
    q.source_shift_mm = shift_mm;
  else if (method == ShiftMethod::SourceAxial)
    q.source_axial_shift_mm = shift_mm;
  return q;
}

double pupilPositionMm(const Scene& scene, double gaze_deg, GazeAxis axis) {
  const EyePlacement e = axis == GazeAxis::Yaw ? placeEye(scene, gaze_deg, 0.0) : placeEye(scene, 0.0, gaze_deg);
  return axis == GazeAxis::Yaw ? e.pupil_center.x() : e.pupil_center.y();
}

const char* xpRuleName(XpRule r) {
  return r == XpRule::FollowFocus ? "follow-focus" : "plateau-middle";
}

std::optional<XpRule> parseXpRule(const std::string& name) {
  if (name == "plateau-middle") return XpRule::PlateauMiddle;
  if (name == "follow-focus") return XpRule::FollowFocus;
  return std::nullopt;
}

namespace {

// The seed's rule (header comment): the secant method on the focus's lateral miss m(s) of the
// rotated pupil centre, from the geometric guess. m is piecewise smooth (the set of lit rays
// changes by single rays as the plate moves), so the secant step is clamped and the iteration
// stops at the tolerance or after a bounded number of steps, keeping the smallest |m| seen.
GazeSample followFocusShift(const Scene& scene, const FovEvaluator& eval, double gaze_deg, GazeAxis axis,
                            const GazeStudyOptions& options, double guess) {
  const EyePlacement eye = axis == GazeAxis::Yaw ? placeEye(scene, gaze_deg, 0.0) : placeEye(scene, 0.0, gaze_deg);
  const int k = axis == GazeAxis::Yaw ? 0 : 1;
  auto missAt = [&](double s) -> Eigen::Vector3d {
    const std::array<double, 2> shift = axis == GazeAxis::Yaw ? std::array<double, 2>{s, 0.0} : std::array{0.0, s};
    const auto f = hoeFocus(scene, shift, options.focus);
    if (!f)
      throw std::runtime_error("follow-focus x_p: no lit ray leaves the HOE towards the eye at a shift of " +
                               std::to_string(s) + " mm");
    return f->focus.point - eye.pupil_center;
  };
  double s0 = guess, s1 = guess + 0.5;
  Eigen::Vector3d m0 = missAt(s0), m1 = missAt(s1);
  double best_s = std::abs(m0[k]) <= std::abs(m1[k]) ? s0 : s1;
  Eigen::Vector3d best_m = std::abs(m0[k]) <= std::abs(m1[k]) ? m0 : m1;
  for (int it = 0; it < 40 && std::abs(best_m[k]) > options.focus_tolerance_mm; ++it) {
    const double slope = (m1[k] - m0[k]) / (s1 - s0);
    // The focus follows the plate about one to one: a flat or reversed secant is a step of
    // the lit-ray set, not the trend; then step by the miss itself.
    const double step = slope > 0.2 && slope < 5.0 ? -m1[k] / slope : -m1[k];
    const double s2 = s1 + std::clamp(step, -2.0, 2.0);
    if (s2 == s1) break;
    s0 = s1;
    m0 = m1;
    s1 = s2;
    m1 = missAt(s1);
    if (std::abs(m1[k]) < std::abs(best_m[k])) {
      best_s = s1;
      best_m = m1;
    }
  }
  GazeSample out;
  out.gaze_deg = gaze_deg;
  out.shift_mm = best_s;
  out.fov = eval(scene, gazeQuery(gaze_deg, axis, ShiftMethod::Hoe, best_s));
  out.pupil_position_mm = k == 0 ? eye.pupil_center.x() : eye.pupil_center.y();
  out.plateau_mm = {best_s, best_s};
  out.best_fov_deg = axisFov(out.fov, axis);
  out.focus_axial_miss_mm = best_m.dot(eye.gaze);
  out.focus_lateral_miss_mm = best_m[k];
  return out;
}

}  // namespace

GazeSample optimiseShift(const Scene& scene, const FovEvaluator& eval, double gaze_deg, GazeAxis axis,
                         ShiftMethod method, const GazeStudyOptions& options) {
  const double pupil = pupilPositionMm(scene, gaze_deg, axis);
  const double pupil0 = pupilPositionMm(scene, 0.0, axis);
  // Geometric guess: a HOE shift moves the Maxwellian focus with it, so follow the pupil.
  // The source shift has no simple guess (it moves along z): bracket around zero, wider.
  const double guess = method == ShiftMethod::Hoe ? pupil - pupil0 : 0.0;
  const double half = method == ShiftMethod::Hoe ? options.shift_half_range_mm : 2.5 * options.shift_half_range_mm;
  if (method == ShiftMethod::Hoe && options.xp_rule == XpRule::FollowFocus)
    return followFocusShift(scene, eval, gaze_deg, axis, options, guess);
  const int n = std::max(3, options.bracket_points);
  // The bracket and the edges read only the FOV along the axis (the sample at x_p has all).
  auto fovAt = [&](double s) {
    FovQuery q = gazeQuery(gaze_deg, axis, method, s);
    q.only_axis = axis == GazeAxis::Yaw ? 0 : 1;
    return axisFov(eval(scene, q), axis);
  };
  if (method == ShiftMethod::None) {
    GazeSample fixed;
    fixed.gaze_deg = gaze_deg;
    fixed.fov = eval(scene, gazeQuery(gaze_deg, axis, method, 0.0));
    fixed.pupil_position_mm = pupil;
    fixed.best_fov_deg = axisFov(fixed.fov, axis);
    return fixed;
  }

  // 1. Coarse bracket: the best FOV F* over the grid and the plateau: from the first to the
  //    last grid point within plateau_tolerance_deg of F* (dips inside it are ray-sampling
  //    noise), its two edges bisected below against the neighbouring grid points outside it.
  //    Unless full_bracket, the grid is walked outwards from the guess (its middle point) and
  //    each side stops after two consecutive points below the level: the FOV is a plateau
  //    with cliffs or slopes, so the points beyond cannot raise F* nor join the plateau and
  //    the result equals the full bracket's (tst_gaze_studies_traced compares them) at about
  //    half the grid evaluations. Unevaluated points count as below the level.
  std::vector<double> grid(n), values(n, -std::numeric_limits<double>::infinity());
  for (int i = 0; i < n; ++i) grid[i] = guess - half + 2.0 * half * i / (n - 1);
  if (options.full_bracket) {
    for (int i = 0; i < n; ++i) values[i] = fovAt(grid[i]);
  } else {
    const int centre = (n - 1) / 2;
    values[centre] = fovAt(grid[centre]);
    double running_best = values[centre];
    for (const int step : {-1, +1}) {
      int below = 0;
      for (int i = centre + step; i >= 0 && i < n && below < 2; i += step) {
        values[i] = fovAt(grid[i]);
        running_best = std::max(running_best, values[i]);
        below = values[i] < running_best - options.plateau_tolerance_deg ? below + 1 : 0;
      }
    }
  }
  const double best = *std::max_element(values.begin(), values.end());
  const double level = best - options.plateau_tolerance_deg;
  int first = 0, last = n - 1;
  while (first < n - 1 && values[first] < level) ++first;
  while (last > 0 && values[last] < level) --last;
  auto edge = [&](double in, double out) {
    for (int k = 0; k < options.edge_bisections; ++k) {
      const double mid = 0.5 * (in + out);
      (fovAt(mid) >= level ? in : out) = mid;
    }
    return 0.5 * (in + out);
  };
  double lo = grid[first], hi = grid[last];
  if (best > 0) {
    if (first > 0) lo = edge(grid[first], grid[first - 1]);
    if (last < n - 1) hi = edge(grid[last], grid[last + 1]);
  } else {
    lo = hi = guess;  // no light in the pupil anywhere in the bracket
  }
  // 3. x_p: the middle of the plateau; the FOV reported is the one traced there.
  GazeSample out;
  out.gaze_deg = gaze_deg;
  out.shift_mm = 0.5 * (lo + hi);
  out.fov = eval(scene, gazeQuery(gaze_deg, axis, method, out.shift_mm));
  out.pupil_position_mm = pupil;
  out.plateau_mm = {lo, hi};
  out.best_fov_deg = best;
  return out;
}

std::vector<double> sweepGazes(double from_deg, double to_deg, double step_deg) {
  if (!(step_deg > 0) || !(to_deg >= from_deg)) throw std::invalid_argument("gaze range: need from <= to and step > 0");
  // The count is bounded before the list is built: with from = to = 1e300 or a step of 5e-324,
  // from + i * step never passes `to` and the loop alone would grow the list until bad_alloc.
  const double span = (to_deg - from_deg) / step_deg;
  constexpr auto kMax = static_cast<std::size_t>(analysis::kMaxGazeSamples);  // the CLI's cap
  if (!(span <= static_cast<double>(kMax)))
    throw std::invalid_argument("gaze range: from..to by step gives more than " + std::to_string(kMax) +
                                " gaze samples");
  std::vector<double> gazes;
  for (std::size_t i = 0; i <= kMax && static_cast<double>(i) <= span + 1e-6; ++i) {
    const double g = from_deg + static_cast<double>(i) * step_deg;
    if (g > to_deg + 1e-9 * std::max(1.0, std::abs(to_deg))) break;
    gazes.push_back(g);
  }
  return gazes;
}

StudyOutcome<GazeSweepResult> sweepGaze(const Scene& scene, const FovEvaluator& eval, double from_deg, double to_deg,
                                        double step_deg, GazeAxis axis, ShiftMethod method,
                                        const GazeStudyOptions& options, const StudyControl& control) {
  const std::vector<double> gazes = sweepGazes(from_deg, to_deg, step_deg);
  // Samples, then the zero-gaze reference as the last job.
  auto runs = runSamples<GazeSample>(
      gazes.size() + 1,
      [&](std::size_t i) {
        return optimiseShift(scene, eval, i < gazes.size() ? gazes[i] : 0.0, axis, method, options);
      },
      control);
  if (!runs.ok()) return {};
  const GazeSample reference = runs.value->back();
  runs.value->pop_back();
  return finishSweep(scene, eval, std::move(*runs.value), reference, axis, method, options, control);
}

void setEyeBoxBorders(EyeBox& eb, const GazeSample& low, bool low_bounded, const GazeSample& high, bool high_bounded) {
  eb.gaze_range_deg = {low.gaze_deg, high.gaze_deg};
  eb.pupil_range_mm = {low.pupil_position_mm, high.pupil_position_mm};
  eb.width_mm = high.pupil_position_mm - low.pupil_position_mm;
  eb.travel_mm = {low.shift_mm, high.shift_mm};
  eb.lower_bounded = low_bounded;
  eb.upper_bounded = high_bounded;
}

StudyOutcome<GazeSweepResult> finishSweep(const Scene& scene, const FovEvaluator& eval, std::vector<GazeSample> samples,
                                          const GazeSample& reference, GazeAxis axis, ShiftMethod method,
                                          const GazeStudyOptions& options, const StudyControl& control) {
  StudyOutcome<GazeSweepResult> out;
  GazeSweepResult r;
  r.axis = axis;
  r.method = method;
  r.samples = std::move(samples);
  const double threshold = eyeBoxThresholdDeg(axisFov(reference.fov, axis), options);
  auto good = [&](const GazeSample& s) { return axisFov(s.fov, axis) >= threshold; };

  // Walk out from zero gaze on each side; refine the first failure by bisection.
  EyeBox& eb = r.eyebox;
  eb.reference_fov_deg = axisFov(reference.fov, axis);
  // The sweep's own samples along each side (looked up by gaze), new searches for the bisections.
  std::vector<double> gazes;
  std::map<double, const GazeSample*> by_gaze;
  for (const auto& s : r.samples) gazes.push_back(s.gaze_deg), by_gaze[s.gaze_deg] = &s;
  const GazeSampleSource computed = [&by_gaze](double g) { return *by_gaze.at(g); };
  const GazeSampleSource search = [&](double g) { return optimiseShift(scene, eval, g, axis, method, options); };
  auto border = [&](int direction) {
    return eyeBoxBorder(gazes, direction, reference, good, computed, search, options.border_bisections, control);
  };
  auto borders = runSamples<std::optional<std::pair<GazeSample, bool>>>(
      2, [&](std::size_t i) { return border(i == 0 ? -1 : +1); }, control);
  if (!borders.ok() || !(*borders.value)[0] || !(*borders.value)[1]) return out;
  const auto& [low, low_bounded] = *(*borders.value)[0];
  const auto& [high, high_bounded] = *(*borders.value)[1];
  setEyeBoxBorders(eb, low, low_bounded, high, high_bounded);
  out.status = StudyStatus::Completed;
  out.value = std::move(r);
  return out;
}

StudyOutcome<std::vector<SensitivitySample>> sensitivitySweep(const Scene& scene, const FovEvaluator& eval,
                                                              const std::string& path, double from, double to,
                                                              int steps, const StudyControl& control,
                                                              const std::optional<GazeStudyOptions>& follow) {
  if (steps < 1) throw std::invalid_argument("steps must be >= 1");
  std::vector<double> values(steps);
  std::vector<Scene> scenes;
  scenes.reserve(steps);
  for (int i = 0; i < steps; ++i) {
    values[i] = steps == 1 ? from : from + (to - from) * i / (steps - 1);
    scenes.push_back(withParameter(scene, path, values[i]));  // every value validated before any work
  }
  return runSamples<SensitivitySample>(
      steps,
      [&](std::size_t i) {
        FovQuery q;
        q.gaze_deg = scenes[i].eye.gaze_deg;
        if (follow)
          for (int k = 0; k < 2; ++k)
            if (q.gaze_deg[k] != 0.0)
              q.hoe_shift_mm[k] = optimiseShift(scenes[i], eval, q.gaze_deg[k],
                                                k == 0 ? GazeAxis::Yaw : GazeAxis::Pitch, ShiftMethod::Hoe, *follow)
                                      .shift_mm;
        return SensitivitySample{values[i], eval(scenes[i], q), q.hoe_shift_mm};
      },
      control);
}

}  // namespace fovea

#include "model/analysis/tolerance_spec.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <variant>

#include "model/io/json_fields.h"
#include "model/scene/scene_fields.h"  // numberAt
#include "model/scene/scene_io.h"      // formatNumber

namespace fovea {

namespace {

std::uint64_t mix64(std::uint64_t z) {  // splitmix64 finaliser (Steele, Lea & Flood 2014)
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

double normalCdf(double z) {
  return 0.5 * std::erfc(-z / std::numbers::sqrt2);
}

// Inverse of the standard normal CDF: Acklam's rational approximation (relative error
// 1.15e-9) polished by one Halley step on erfc, which brings it to double precision.
double normalQuantile(double p) {
  static const double a[] = {-3.969683028665376e+01, 2.209460984245205e+02,  -2.759285104469687e+02,
                             1.383577518672690e+02,  -3.066479806614716e+01, 2.506628277459239e+00};
  static const double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                             6.680131188771972e+01, -1.328068155288572e+01};
  static const double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                             -2.549732539343734e+00, 4.374664141464968e+00,  2.938163982698783e+00};
  static const double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                             3.754408661907416e+00};
  const double lo = 0.02425;
  double x;
  if (p < lo) {
    const double q = std::sqrt(-2 * std::log(p));
    x = (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
        ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
  } else if (p <= 1 - lo) {
    const double q = p - 0.5, r = q * q;
    x = (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
        (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1);
  } else {
    const double q = std::sqrt(-2 * std::log(1 - p));
    x = -(((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
        ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
  }
  const double e = normalCdf(x) - p;
  const double u = e * std::sqrt(2 * std::numbers::pi) * std::exp(0.5 * x * x);
  return x - u / (1 + 0.5 * x * u);
}

}  // namespace

double counterUniform(std::uint64_t seed, std::uint64_t trial, std::uint64_t stream, std::uint64_t parameter) {
  const std::uint64_t h = mix64(mix64(mix64(mix64(seed) ^ trial) ^ (stream + 0x51ed27ULL)) ^ parameter);
  return (static_cast<double>(h >> 11) + 0.5) * 0x1.0p-53;  // in (0, 1)
}

double ToleranceParameter::quantile(double u) const {
  switch (distribution) {
    case Distribution::Uniform:
      return mean + half_width * (2 * u - 1);
    case Distribution::Normal:
      return mean + sigma * normalQuantile(u);
    case Distribution::TruncatedNormal: {
      const double a = normalCdf(-limit / sigma), b = normalCdf(limit / sigma);
      return mean + sigma * normalQuantile(a + u * (b - a));
    }
  }
  return mean;
}

double ToleranceParameter::width() const {
  return distribution == Distribution::Uniform ? half_width : sigma;
}

double ToleranceParameter::scaledDensityRatio(double x, double c) const {
  const double z = x - mean;
  switch (distribution) {
    case Distribution::Uniform:
      return std::abs(z) <= c * half_width ? 1.0 / c : 0.0;
    case Distribution::TruncatedNormal:
      if (std::abs(z) > c * limit) return 0.0;
      [[fallthrough]];
    case Distribution::Normal:
      // phi(z / (c sigma)) / (c sigma) over phi(z / sigma) / sigma (the truncation mass is the
      // same for both: limit scales with sigma).
      return std::exp(-0.5 * z * z / (sigma * sigma) * (1.0 / (c * c) - 1.0)) / c;
  }
  return 0.0;
}

const std::vector<std::string>& toleranceFigureNames() {
  static const std::vector<std::string> names{"fov_min_deg", "fov_zero_gaze_deg", "eyebox_mm", "inset_error_deg",
                                              "mean_efficiency"};
  return names;
}

ToleranceSpec parseToleranceSpec(const nlohmann::json& j, const std::string& source) {
  ToleranceSpec s;
  s.source = j;
  const JsonFields doc(j, source);  // every field typed and range-checked (model/io/json_fields.h)
  doc.text("format", {"fovea-tolerance"});
  doc.known({"version", "notes"});  // free text and the format's version, not read
  const std::vector<JsonFields> params = doc.objects("parameters", true, kMaxToleranceParameters);
  if (params.empty()) doc.fail("parameters", "must be a non-empty array");
  const Range positive = Range::positive();
  for (std::size_t i = 0; i < params.size(); ++i) {
    const JsonFields& p = params[i];
    ToleranceParameter t;
    const std::string kind = p.text(
        "kind", {"scene", "laser_temperature", "stage_repeatability", "stage_backlash", "gaze_tracker"}, "scene");
    if (kind == "scene") {
      t.kind = ToleranceKind::Scene;
      // A number of the scene file; integer fields (pixel counts) are refused against the scene
      // (checkToleranceSpecPaths), the path's syntax here.
      t.path = p.text("path", {}, std::nullopt, true);
    } else if (kind == "laser_temperature") {
      t.kind = ToleranceKind::LaserTemperature;
      const nlohmann::json* d = p.get("drift_nm_per_K", true);
      if (d->is_array())
        t.drift_nm_per_K = p.numbers("drift_nm_per_K", Range::any(), 0, 16);
      else
        t.drift_nm_per_K = {p.number("drift_nm_per_K", Range::any())};
    } else if (kind == "stage_repeatability") {
      t.kind = ToleranceKind::StageRepeatability;
    } else if (kind == "stage_backlash") {
      t.kind = ToleranceKind::StageBacklash;
    } else {
      t.kind = ToleranceKind::GazeTracker;
    }
    t.name = p.text("name", {}, t.kind == ToleranceKind::Scene ? t.path : kind, true);
    const std::string dist = p.text("distribution", {"normal", "uniform", "truncated_normal"}, "normal");
    t.mean = p.number("mean", Range::any(), 0.0);
    if (dist == "normal") {
      t.distribution = Distribution::Normal;
      t.sigma = p.number("sigma", positive);
    } else if (dist == "uniform") {
      t.distribution = Distribution::Uniform;
      t.half_width = p.number("half_width", positive);
    } else {
      t.distribution = Distribution::TruncatedNormal;
      t.sigma = p.number("sigma", positive);
      t.limit = p.number("limit", positive);
    }
    for (const auto& q : s.parameters)
      if (q.name == t.name) p.fail(p.at("name"), "duplicate parameter name \"" + t.name + "\"");
    s.parameters.push_back(std::move(t));
  }
  const nlohmann::json no_gaze = nlohmann::json::object();
  const JsonFields gaze = doc.has("gaze") ? *doc.object("gaze") : JsonFields(no_gaze, source, "gaze");
  s.axis = gaze.text("axis", {"yaw", "pitch"}, "yaw") == "yaw" ? GazeAxis::Yaw : GazeAxis::Pitch;
  // Gazes within the eye's range (the CLI's --gaze-* limit); at most 200 steps, the list built by
  // count (from + i step never passes `to` when from = to = 1e300 or step = 5e-324).
  const Range gaze_range = Range::closed(-kToleranceGazeLimitDeg, kToleranceGazeLimitDeg);
  const double from = gaze.number("from_deg", gaze_range, -20.0), to = gaze.number("to_deg", gaze_range, 20.0);
  const double step = gaze.number("step_deg", Range::openClosed(0, 2 * kToleranceGazeLimitDeg), 10.0);
  if (!(to >= from)) gaze.fail("gaze", "need from_deg <= to_deg");
  const double span = (to - from) / step;
  if (!(span <= 200))
    gaze.fail("gaze", "at most 200 steps from from_deg to to_deg, got " + formatNumber(std::floor(span)));
  for (int i = 0; i <= static_cast<int>(std::floor(span + 1e-9)); ++i) s.gazes_deg.push_back(from + i * step);
  const std::string shift = doc.text("shift", {"hoe", "source", "none"}, "hoe");
  s.method = shift == "hoe" ? ShiftMethod::Hoe : shift == "source" ? ShiftMethod::Source : ShiftMethod::None;
  s.compensator =
      doc.text("compensator", {"refind", "fixed"}, "refind") == "refind" ? Compensator::Refind : Compensator::Fixed;
  s.eyebox_tolerance_deg = doc.number("eyebox_tolerance_deg", positive, 3.0);
  if (const auto pass = doc.object("pass")) {
    const auto& names = toleranceFigureNames();
    for (const auto& [name, b] : j["pass"].items()) {
      const std::string at = pass->at(name);
      if (std::find(names.begin(), names.end(), name) == names.end()) pass->fail(at, "unknown figure");
      const JsonFields bound = *pass->object(name, true);
      if (!bound.has("min") && !bound.has("max")) bound.fail(at, "must be an object with \"min\" and/or \"max\"");
      FigureBound fb;
      if (bound.has("min")) fb.min = bound.number("min", Range::any());
      if (bound.has("max")) fb.max = bound.number("max", Range::any());
      s.pass.emplace_back(name, fb);
    }
  }
  s.target_yield = doc.number("target_yield", Range::open(0, 1), 0.9);
  s.sobol = doc.text("sensitivity", {"saltelli", "none"}, "saltelli") == "saltelli";
  s.fov_tolerance_deg = doc.number("fov_tolerance_deg", positive, 0.02);
  if (doc.has("wavelength_nm")) s.wavelength_nm = doc.number("wavelength_nm", Range::openClosed(0, 2000));
  if (const auto opt = doc.object("optimiser")) {
    s.optimiser.bracket_points = static_cast<int>(opt->integer("bracket_points", 3, 65, 9));
    s.optimiser.edge_bisections = static_cast<int>(opt->integer("edge_bisections", 0, 20, 4));
    s.optimiser.plateau_tolerance_deg = opt->number("plateau_tolerance_deg", positive, 2.0);
  }
  doc.rejectUnknownKeys();
  return s;
}

void checkToleranceSpecPaths(const ToleranceSpec& spec, const Scene& scene, const std::string& source) {
  Scene copy = scene;
  for (std::size_t i = 0; i < spec.parameters.size(); ++i) {
    const ToleranceParameter& p = spec.parameters[i];
    if (p.kind != ToleranceKind::Scene) continue;
    const std::string at = source + ": parameters[" + std::to_string(i) + "].path: ";
    std::variant<double*, int*> ref;
    try {
      ref = numberAt(copy, p.path);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(at + e.what());
    }
    if (std::holds_alternative<int*>(ref))
      throw std::invalid_argument(at + "\"" + p.path +
                                  "\" is an integer field of the scene; a tolerance offsets real numbers only");
  }
}

std::vector<double> trialInputs(const ToleranceSpec& spec, std::uint64_t seed, std::uint64_t trial) {
  const std::size_t k = spec.parameters.size();
  std::uint64_t row = trial;
  std::size_t role = 0;
  if (spec.sobol) {
    row = trial / (k + 2);
    role = trial % (k + 2);
  }
  std::vector<double> x(k);
  for (std::size_t p = 0; p < k; ++p) {
    const std::uint64_t stream = role == 1 || (role >= 2 && role - 2 == p) ? 1 : 0;
    x[p] = spec.parameters[p].quantile(counterUniform(seed, row, stream, p));
  }
  return x;
}

}  // namespace fovea

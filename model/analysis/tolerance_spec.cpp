#include "model/analysis/tolerance_spec.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

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

[[noreturn]] void fail(const std::string& where, const std::string& why) {
  throw std::invalid_argument("tolerance spec: " + where + ": " + why);
}

double positive(const nlohmann::json& j, const char* key, const std::string& where, bool required = true,
                double fallback = 0) {
  if (!j.contains(key)) {
    if (required) fail(where, std::string("missing \"") + key + "\"");
    return fallback;
  }
  if (!j[key].is_number()) fail(where, std::string("\"") + key + "\" must be a number");
  const double v = j[key].get<double>();
  if (!std::isfinite(v) || !(v > 0)) fail(where, std::string("\"") + key + "\" must be a finite number > 0");
  return v;
}

double finiteNumber(const nlohmann::json& j, const char* key, const std::string& where, double fallback) {
  if (!j.contains(key)) return fallback;
  if (!j[key].is_number() || !std::isfinite(j[key].get<double>()))
    fail(where, std::string("\"") + key + "\" must be a finite number");
  return j[key].get<double>();
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

ToleranceSpec parseToleranceSpec(const nlohmann::json& j) {
  ToleranceSpec s;
  s.source = j;
  if (!j.is_object()) fail("document", "must be a JSON object");
  if (j.value("format", std::string()) != "fovea-tolerance") fail("format", "must be \"fovea-tolerance\"");
  if (!j.contains("parameters") || !j["parameters"].is_array() || j["parameters"].empty())
    fail("parameters", "must be a non-empty array");
  for (std::size_t i = 0; i < j["parameters"].size(); ++i) {
    const nlohmann::json& p = j["parameters"][i];
    const std::string where = "parameters[" + std::to_string(i) + "]";
    if (!p.is_object()) fail(where, "must be an object");
    ToleranceParameter t;
    const std::string kind = p.value("kind", std::string("scene"));
    if (kind == "scene") {
      t.kind = ToleranceKind::Scene;
      if (!p.contains("path") || !p["path"].is_string() || p["path"].get<std::string>().empty())
        fail(where, "kind \"scene\" needs a \"path\" (a number of the scene file, e.g. \"hoe.position_mm[0]\")");
      t.path = p["path"].get<std::string>();
    } else if (kind == "laser_temperature") {
      t.kind = ToleranceKind::LaserTemperature;
      if (!p.contains("drift_nm_per_K")) fail(where, "kind \"laser_temperature\" needs \"drift_nm_per_K\"");
      const nlohmann::json& d = p["drift_nm_per_K"];
      if (d.is_number()) {
        t.drift_nm_per_K = {d.get<double>()};
      } else if (d.is_array() && !d.empty()) {
        for (const auto& v : d) {
          if (!v.is_number()) fail(where, "\"drift_nm_per_K\" must hold numbers");
          t.drift_nm_per_K.push_back(v.get<double>());
        }
      } else {
        fail(where, "\"drift_nm_per_K\" must be a number or an array of numbers");
      }
      for (double v : t.drift_nm_per_K)
        if (!std::isfinite(v)) fail(where, "\"drift_nm_per_K\" must be finite");
    } else if (kind == "stage_repeatability") {
      t.kind = ToleranceKind::StageRepeatability;
    } else if (kind == "stage_backlash") {
      t.kind = ToleranceKind::StageBacklash;
    } else if (kind == "gaze_tracker") {
      t.kind = ToleranceKind::GazeTracker;
    } else {
      fail(where, "unknown kind \"" + kind +
                      "\" (scene, laser_temperature, stage_repeatability, stage_backlash, gaze_tracker)");
    }
    t.name = p.value("name", t.kind == ToleranceKind::Scene ? t.path : kind);
    const std::string dist = p.value("distribution", std::string("normal"));
    t.mean = finiteNumber(p, "mean", where, 0.0);
    if (dist == "normal") {
      t.distribution = Distribution::Normal;
      t.sigma = positive(p, "sigma", where);
    } else if (dist == "uniform") {
      t.distribution = Distribution::Uniform;
      t.half_width = positive(p, "half_width", where);
    } else if (dist == "truncated_normal") {
      t.distribution = Distribution::TruncatedNormal;
      t.sigma = positive(p, "sigma", where);
      t.limit = positive(p, "limit", where);
    } else {
      fail(where, "unknown distribution \"" + dist + "\" (normal, uniform, truncated_normal)");
    }
    for (const auto& q : s.parameters)
      if (q.name == t.name) fail(where, "duplicate parameter name \"" + t.name + "\"");
    s.parameters.push_back(std::move(t));
  }
  const nlohmann::json gaze = j.value("gaze", nlohmann::json::object());
  if (!gaze.is_object()) fail("gaze", "must be an object");
  const std::string axis = gaze.value("axis", std::string("yaw"));
  if (axis == "yaw")
    s.axis = GazeAxis::Yaw;
  else if (axis == "pitch")
    s.axis = GazeAxis::Pitch;
  else
    fail("gaze.axis", "must be \"yaw\" or \"pitch\"");
  const double from = finiteNumber(gaze, "from_deg", "gaze", -20.0), to = finiteNumber(gaze, "to_deg", "gaze", 20.0);
  const double step = positive(gaze, "step_deg", "gaze", false, 10.0);
  if (!(to >= from) || (to - from) / step > 200) fail("gaze", "need from_deg <= to_deg and at most 200 steps");
  for (int i = 0;; ++i) {
    const double g = from + i * step;
    if (g > to + 1e-9) break;
    s.gazes_deg.push_back(g);
  }
  const std::string shift = j.value("shift", std::string("hoe"));
  if (shift == "hoe")
    s.method = ShiftMethod::Hoe;
  else if (shift == "source")
    s.method = ShiftMethod::Source;
  else if (shift == "none")
    s.method = ShiftMethod::None;
  else
    fail("shift", "must be \"hoe\", \"source\" or \"none\"");
  const std::string comp = j.value("compensator", std::string("refind"));
  if (comp == "refind")
    s.compensator = Compensator::Refind;
  else if (comp == "fixed")
    s.compensator = Compensator::Fixed;
  else
    fail("compensator", "must be \"refind\" (x_p re-found per gaze on each unit) or \"fixed\" (the nominal x_p)");
  s.eyebox_tolerance_deg = positive(j, "eyebox_tolerance_deg", "document", false, 3.0);
  if (j.contains("pass")) {
    if (!j["pass"].is_object()) fail("pass", "must be an object of figure -> {\"min\": .., \"max\": ..}");
    for (const auto& [name, b] : j["pass"].items()) {
      const auto& names = toleranceFigureNames();
      if (std::find(names.begin(), names.end(), name) == names.end()) fail("pass." + name, "unknown figure");
      if (!b.is_object() || (!b.contains("min") && !b.contains("max")))
        fail("pass." + name, "must be an object with \"min\" and/or \"max\"");
      FigureBound fb;
      if (b.contains("min")) fb.min = finiteNumber(b, "min", "pass." + name, 0);
      if (b.contains("max")) fb.max = finiteNumber(b, "max", "pass." + name, 0);
      s.pass.emplace_back(name, fb);
    }
  }
  s.target_yield = finiteNumber(j, "target_yield", "document", 0.9);
  if (!(s.target_yield > 0 && s.target_yield < 1)) fail("target_yield", "must be in (0, 1)");
  const std::string sens = j.value("sensitivity", std::string("saltelli"));
  if (sens == "saltelli")
    s.sobol = true;
  else if (sens == "none")
    s.sobol = false;
  else
    fail("sensitivity", "must be \"saltelli\" or \"none\"");
  s.fov_tolerance_deg = positive(j, "fov_tolerance_deg", "document", false, 0.02);
  if (j.contains("wavelength_nm")) s.wavelength_nm = positive(j, "wavelength_nm", "document");
  const nlohmann::json opt = j.value("optimiser", nlohmann::json::object());
  s.optimiser.bracket_points = opt.value("bracket_points", 9);
  s.optimiser.edge_bisections = opt.value("edge_bisections", 4);
  s.optimiser.plateau_tolerance_deg = opt.value("plateau_tolerance_deg", 2.0);
  if (s.optimiser.bracket_points < 3 || s.optimiser.bracket_points > 65 || s.optimiser.edge_bisections < 0 ||
      s.optimiser.edge_bisections > 20 || !(s.optimiser.plateau_tolerance_deg > 0))
    fail("optimiser", "bracket_points 3..65, edge_bisections 0..20, plateau_tolerance_deg > 0");
  return s;
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

#include "model/analysis/analysis_parameters.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace fovea::analysis {

ParameterSpec number(std::string name, std::string label, std::string unit, nlohmann::json default_value,
                     double minimum, double maximum, int decimals, std::string help) {
  ParameterSpec p;
  p.name = std::move(name);
  p.label = std::move(label);
  p.unit = std::move(unit);
  p.kind = ParameterKind::Number;
  p.default_value = std::move(default_value);
  p.minimum = minimum;
  p.maximum = maximum;
  p.decimals = decimals;
  p.help = std::move(help);
  return p;
}

ParameterSpec positive(std::string name, std::string label, std::string unit, nlohmann::json default_value,
                       double maximum, int decimals, std::string help) {
  ParameterSpec p = number(std::move(name), std::move(label), std::move(unit), std::move(default_value), 0.0, maximum,
                           decimals, std::move(help));
  p.minimum_exclusive = true;
  return p;
}

ParameterSpec integer(std::string name, std::string label, int default_value, int minimum, int maximum,
                      std::string help) {
  ParameterSpec p = number(std::move(name), std::move(label), {}, default_value, minimum, maximum, 0, std::move(help));
  p.kind = ParameterKind::Integer;
  return p;
}

ParameterSpec choice(std::string name, std::string label, std::vector<std::string> choices, std::string default_value,
                     std::string help) {
  ParameterSpec p;
  p.name = std::move(name);
  p.label = std::move(label);
  p.kind = ParameterKind::Choice;
  p.choices = std::move(choices);
  p.default_value = std::move(default_value);
  p.help = std::move(help);
  return p;
}

ParameterSpec text(std::string name, std::string label, std::vector<std::string> suggestions, std::string default_value,
                   std::string help) {
  ParameterSpec p =
      choice(std::move(name), std::move(label), std::move(suggestions), std::move(default_value), std::move(help));
  p.kind = ParameterKind::Text;
  return p;
}

ParameterSpec filePath(std::string name, std::string label, std::string unset_meaning, std::string help) {
  ParameterSpec p;
  p.name = std::move(name);
  p.label = std::move(label);
  p.kind = ParameterKind::FilePath;
  p.default_value = nullptr;
  p.unset_meaning = std::move(unset_meaning);
  p.help = std::move(help);
  return p;
}

ParameterSpec gazeAngle(std::string name, std::string label, nlohmann::json default_value, std::string help) {
  return number(std::move(name), std::move(label), "deg", std::move(default_value), -kGazeLimitDeg, kGazeLimitDeg, 2,
                std::move(help));
}

namespace {
std::string formatNumber(double x) {
  std::ostringstream s;
  s << std::setprecision(10) << x;
  return s.str();
}
std::string withUnit(double x, const std::string& unit) {
  return formatNumber(x) + (unit.empty() ? "" : " " + unit);
}
std::string shown(const nlohmann::json& v) {
  return v.is_string() ? v.get<std::string>() : v.dump();
}
}  // namespace

std::string rangeText(const ParameterSpec& spec) {
  const bool has_min = spec.minimum > -std::numeric_limits<double>::max();
  const bool has_max = spec.maximum < std::numeric_limits<double>::max();
  if (spec.minimum_exclusive && spec.minimum == 0 && has_max)
    return "must be > 0 and <= " + withUnit(spec.maximum, spec.unit);
  if (spec.minimum_exclusive) return "must be > " + withUnit(spec.minimum, spec.unit);
  if (has_min && has_max)
    return "must lie in [" + formatNumber(spec.minimum) + ", " + formatNumber(spec.maximum) + "]" +
           (spec.unit.empty() ? "" : " " + spec.unit);
  if (has_min) return "must be >= " + withUnit(spec.minimum, spec.unit);
  if (has_max) return "must be <= " + withUnit(spec.maximum, spec.unit);
  return "must be a finite number";
}

std::optional<std::string> validateValue(const ParameterSpec& spec, nlohmann::json& value) {
  if (value.is_null()) {
    if (spec.default_value.is_null()) return std::nullopt;
    return std::string("a value is needed");
  }
  switch (spec.kind) {
    case ParameterKind::Number:
    case ParameterKind::Integer: {
      if (!value.is_number()) return "must be a number, got '" + shown(value) + "'";
      const double x = value.get<double>();
      if (!std::isfinite(x)) return "must be a finite number, got " + formatNumber(x);
      const bool below = spec.minimum_exclusive ? !(x > spec.minimum) : x < spec.minimum;
      if (below || x > spec.maximum) return rangeText(spec) + ", got " + formatNumber(x);
      if (spec.kind == ParameterKind::Integer) {
        if (std::floor(x) != x) return "must be a whole number, got " + formatNumber(x);
        value = static_cast<long long>(x);
      }
      return std::nullopt;
    }
    case ParameterKind::Choice: {
      const std::string v = value.is_string() ? value.get<std::string>() : value.dump();
      if (std::find(spec.choices.begin(), spec.choices.end(), v) != spec.choices.end()) {
        value = v;
        return std::nullopt;
      }
      std::string all;
      for (const auto& c : spec.choices) all += (all.empty() ? "" : ", ") + c;
      return "expected one of " + all + ", got '" + v + "'";
    }
    case ParameterKind::Text:
    case ParameterKind::FilePath: {
      std::string v = value.is_string() ? value.get<std::string>() : value.dump();
      const auto first = v.find_first_not_of(" \t\r\n");
      const auto last = v.find_last_not_of(" \t\r\n");
      v = first == std::string::npos ? std::string() : v.substr(first, last - first + 1);
      if (v.empty()) return std::string("must not be empty");
      if (spec.kind == ParameterKind::FilePath) {
        std::error_code ec;
        if (!std::filesystem::exists(v, ec)) return "no such file '" + v + "'";
        if (!std::filesystem::is_regular_file(v, ec)) return "'" + v + "' is not a regular file";
        if (!std::ifstream(v).good()) return "cannot read '" + v + "'";
      }
      value = v;
      return std::nullopt;
    }
  }
  return std::nullopt;
}

std::optional<std::string> parseValueText(const ParameterSpec& spec, const std::string& text, nlohmann::json& value) {
  if (spec.kind == ParameterKind::Choice || spec.kind == ParameterKind::Text || spec.kind == ParameterKind::FilePath) {
    value = text;
    return std::nullopt;
  }
  // strtod accepts "nan", "inf" and hex floats; they are refused by validateValue with a
  // message naming the value rather than as unreadable text.
  const char* begin = text.c_str();
  char* end = nullptr;
  const double x = std::strtod(begin, &end);
  if (text.empty() || end != begin + text.size()) return "'" + text + "' is not a number";
  value = x;
  return std::nullopt;
}

std::string ParameterProblem::text(const std::string& prefix) const {
  return parameter.empty() ? message : prefix + parameter + ": " + message;
}

double numberOf(const nlohmann::json& values, const std::string& name) {
  return values.at(name).get<double>();
}
std::optional<double> optionalNumberOf(const nlohmann::json& values, const std::string& name) {
  const auto it = values.find(name);
  if (it == values.end() || it->is_null()) return std::nullopt;
  return it->get<double>();
}
int integerOf(const nlohmann::json& values, const std::string& name) {
  return static_cast<int>(values.at(name).get<long long>());
}
std::string textOf(const nlohmann::json& values, const std::string& name) {
  return values.at(name).get<std::string>();
}

std::optional<ParameterProblem> checkGazeRange(const nlohmann::json& values) {
  const double from = numberOf(values, "gaze-from"), to = numberOf(values, "gaze-to");
  const double step = numberOf(values, "gaze-step");
  if (!(to >= from)) return ParameterProblem{"gaze-to", "must be >= gaze-from"};
  // Samples of from, from + step, ..., to (sweepGaze's count); refused above the bound
  // before anything is allocated.
  const double intervals = (to - from) / step;
  const double samples = std::floor(intervals + 1e-9) + 1;
  if (intervals > kMaxGazeSamples)
    return ParameterProblem{"gaze-step", "more than " + std::to_string(kMaxGazeSamples) + " gaze samples (" +
                                             formatNumber(samples) + " from " + formatNumber(from) + " to " +
                                             formatNumber(to) + " by " + formatNumber(step) + " deg)"};
  return std::nullopt;
}

}  // namespace fovea::analysis

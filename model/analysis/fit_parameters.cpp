#include "model/analysis/fit_parameters.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <variant>

#include "model/scene/scene_fields.h"
#include "model/scene/scene_parameters.h"

namespace fovea {

namespace {

double parseNumber(const std::string& text, const std::string& spec) {
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (text.empty() || used != text.size() || !std::isfinite(v))
    throw std::invalid_argument("free parameter \"" + spec + "\": \"" + text + "\" is not a finite number");
  return v;
}

double defaultHalfWindow(const std::string& unit, double v) {
  if (unit == "deg") return 5.0;
  if (unit == "mm") return std::max(5.0, 0.1 * std::abs(v));
  return v == 0 ? 1.0 : 0.25 * std::abs(v);
}

}  // namespace

FreeParameter parseFreeParameter(const Scene& scene, const std::string& spec) {
  const auto eq = spec.find('=');
  FreeParameter p;
  p.path = spec.substr(0, eq);
  std::string unit;
  const FieldInfo* info = fieldInfoAt(scene, p.path, &unit);
  Scene copy = scene;
  std::variant<double*, int*> target;
  try {
    target = numberAt(copy, p.path);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("free parameter: ") + e.what() +
                                " (a number path of the scene file, e.g. eye.relief_mm, hoe.rotation_deg[0])");
  }
  if (!info || std::holds_alternative<int*>(target))
    throw std::invalid_argument("free parameter " + p.path + ": an integer field cannot be fitted");
  p.unit = unit;
  p.initial = *std::get<double*>(target);
  const Range& range = info->range;
  const double w = defaultHalfWindow(unit, p.initial);
  if (eq == std::string::npos) {
    p.lower = p.initial - w;
    p.upper = p.initial + w;
  } else {
    const std::string b = spec.substr(eq + 1);
    const auto colon = b.find(':');
    if (b.rfind("+-", 0) == 0) {
      const double d = parseNumber(b.substr(2), spec);
      if (!(d > 0)) throw std::invalid_argument("free parameter \"" + spec + "\": the window +-D needs D > 0");
      p.lower = p.initial - d;
      p.upper = p.initial + d;
    } else if (colon != std::string::npos) {
      p.lower = parseNumber(b.substr(0, colon), spec);
      p.upper = parseNumber(b.substr(colon + 1), spec);
    } else {
      throw std::invalid_argument("free parameter \"" + spec + "\": bounds must be LO:HI or +-D");
    }
    if (!(p.lower < p.upper)) throw std::invalid_argument("free parameter \"" + spec + "\": needs LO < HI");
  }
  // Clip to the field's range when the bounds were defaulted or given as +-D; refuse explicit
  // LO:HI outside it. An open bound is kept a margin inside: 1e-9 of the window *after*
  // clipping (of the unclipped +-D window, a large D would push the margin past the scene's
  // own value), and never more than 1e-6 of the way from the scene's value to the bound (on a
  // half-open range the clipped window still grows with D: waist_fwhm_um=+-1e12 kept the
  // search above 300 µm for a scene value of 600).
  using Bound = Range::Bound;
  if (eq == std::string::npos || spec.find("=+-") != std::string::npos) {
    if (range.low != Bound::None) p.lower = std::max(p.lower, range.lo);
    if (range.high != Bound::None) p.upper = std::min(p.upper, range.hi);
    const double margin = 1e-9 * (p.upper - p.lower);
    if (range.low == Bound::Open)
      p.lower = std::max(p.lower, range.lo + std::min(margin, 1e-6 * (p.initial - range.lo)));
    if (range.high == Bound::Open)
      p.upper = std::min(p.upper, range.hi - std::min(margin, 1e-6 * (range.hi - p.initial)));
  } else {
    const double margin = 1e-9 * (p.upper - p.lower);
    double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
    if (range.low != Bound::None) lo = range.lo + (range.low == Bound::Open ? margin : 0.0);
    if (range.high != Bound::None) hi = range.hi - (range.high == Bound::Open ? margin : 0.0);
    if (p.lower < lo || p.upper > hi)
      throw std::invalid_argument("free parameter \"" + spec + "\": bounds leave the field's range " +
                                  info->rangeText());
  }
  if (p.initial < p.lower || p.initial > p.upper)
    throw std::invalid_argument("free parameter \"" + spec + "\": the scene's value " + std::to_string(p.initial) +
                                " lies outside the bounds");
  return p;
}

std::vector<FreeParameter> parseFreeParameters(const Scene& scene, const std::vector<std::string>& specs) {
  std::vector<FreeParameter> out;
  std::set<std::string> seen;
  for (const auto& s : specs) {
    out.push_back(parseFreeParameter(scene, s));
    if (!seen.insert(out.back().path).second)
      throw std::invalid_argument("free parameter " + out.back().path + ": given twice");
  }
  return out;
}

Scene sceneWithValues(const Scene& scene, const std::vector<FreeParameter>& free, const std::vector<double>& values) {
  Scene out = scene;
  for (std::size_t i = 0; i < free.size(); ++i) out = withParameter(out, free[i].path, values.at(i));
  return out;
}

}  // namespace fovea

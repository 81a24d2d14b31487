#include "model/analysis/fit_targets.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>
#include <stdexcept>

#include <tbb/parallel_for.h>

#include "model/scene/scene_fields.h"  // Range

namespace fovea {

namespace {

const std::set<std::string> kTargetKeys{"id", "observable", "value", "sigma", "unit", "source"};

FitTarget parseTarget(const nlohmann::json& j, const std::string& where) {
  if (!j.is_object()) throw std::invalid_argument(where + ": must be an object");
  FitTarget t;
  auto text = [&](const char* key, bool required) {
    if (!j.contains(key)) {
      if (required) throw std::invalid_argument(where + ": missing \"" + key + "\"");
      return std::string();
    }
    if (!j[key].is_string() || j[key].get<std::string>().empty())
      throw std::invalid_argument(where + ": \"" + key + "\" must be a non-empty string");
    return j[key].get<std::string>();
  };
  // Value and sigma in ranges that keep every residual (value - model) / sigma and its square
  // finite: sigma 5e-324 or a value of 1e308 would make chi2 inf (printed null).
  auto number = [&](const char* key, const Range& range) {
    if (!j.contains(key)) throw std::invalid_argument(where + ": missing \"" + key + "\"");
    if (!j[key].is_number())
      throw std::invalid_argument(where + "." + key + ": must be a finite number, got " + j[key].dump());
    if (const std::string p = range.check(j[key].get<double>()); !p.empty())
      throw std::invalid_argument(where + "." + key + ": " + p);
    return j[key].get<double>();
  };
  t.id = text("id", true);
  const std::string at = "target \"" + t.id + "\"";
  t.observable = text("observable", true);
  const ObservableDefinition* def = findObservable(t.observable);
  if (!def)
    throw std::invalid_argument(at + ": unknown observable \"" + t.observable + "\" (known: " + observableNames() +
                                ")");
  t.value = number("value", Range::closed(-kMaxFitTargetValue, kMaxFitTargetValue));
  t.sigma = number("sigma", Range::closed(kMinFitTargetSigma, kMaxFitTargetValue));
  if (j.contains("unit") && !j["unit"].is_string())
    throw std::invalid_argument(at + ": \"unit\" must be a string, got " + j["unit"].dump());
  t.unit = j.value("unit", def->unit);
  if (t.unit != def->unit)
    throw std::invalid_argument(at + ": \"unit\" of " + t.observable + " is \"" + def->unit + "\", got \"" + t.unit +
                                "\"");
  t.source = text("source", false);
  nlohmann::json params = nlohmann::json::object();
  for (const auto& [key, value] : j.items())
    if (!kTargetKeys.count(key)) params[key] = value;
  try {
    t.parameters = completeObservableParameters(*def, params);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(at + ": " + e.what());
  }
  return t;
}

}  // namespace

std::vector<FitTarget> parseFitTargets(const nlohmann::json& j) {
  const nlohmann::json* list = &j;
  if (j.is_object()) {
    if (!j.contains("format") || !j["format"].is_string() || j["format"].get<std::string>() != kFitTargetsFormat)
      throw std::invalid_argument(std::string("targets: \"format\" must be \"") + kFitTargetsFormat + "\"");
    if (!j.contains("version") || !j["version"].is_number_integer() || j["version"].get<long long>() != 1)
      throw std::invalid_argument("version: must be 1");
    if (!j.contains("targets")) throw std::invalid_argument("targets: missing \"targets\" (the list of targets)");
    list = &j["targets"];
  }
  if (!list->is_array()) throw std::invalid_argument("targets: must be a list of targets");
  if (list->empty()) throw std::invalid_argument("targets: the list is empty");
  if (list->size() > kMaxFitTargets)
    throw std::invalid_argument("targets: more than " + std::to_string(kMaxFitTargets) + " targets");
  std::vector<FitTarget> out;
  std::set<std::string> ids;
  for (std::size_t i = 0; i < list->size(); ++i) {
    out.push_back(parseTarget((*list)[i], "targets[" + std::to_string(i) + "]"));
    if (!ids.insert(out.back().id).second)
      throw std::invalid_argument("targets[" + std::to_string(i) + "]: duplicate id \"" + out.back().id + "\"");
  }
  return out;
}

nlohmann::json fitTargetJson(const FitTarget& t) {
  nlohmann::json j{{"id", t.id}, {"observable", t.observable}};
  for (const auto& [k, v] : t.parameters.items()) j[k] = v;
  j["value"] = t.value;
  j["sigma"] = t.sigma;
  j["unit"] = t.unit;
  if (!t.source.empty()) j["source"] = t.source;
  return j;
}

nlohmann::json fitTargetsJson(const std::vector<FitTarget>& targets, const std::string& notes) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& t : targets) list.push_back(fitTargetJson(t));
  nlohmann::json j{{"format", kFitTargetsFormat}, {"version", 1}};
  if (!notes.empty()) j["notes"] = notes;
  j["targets"] = list;
  return j;
}

std::vector<std::string> fitTargetGroups(const std::vector<FitTarget>& targets) {
  std::vector<std::string> out;
  for (const auto& t : targets) {
    const std::size_t dash = t.id.find('-');
    if (dash == std::string::npos || dash == 0) continue;
    const std::string g = t.id.substr(0, dash + 1);
    if (std::find(out.begin(), out.end(), g) == out.end()) out.push_back(g);
  }
  return out;
}

std::vector<FitTarget> selectFitTargets(const std::vector<FitTarget>& targets, const std::string& selection) {
  std::vector<std::string> items;
  std::string cur;
  for (const char c : selection + ",") {
    if (c == ',' || std::isspace(static_cast<unsigned char>(c))) {
      if (!cur.empty()) items.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  if (items.empty()) return targets;
  auto groupsText = [&] {
    std::string g;
    for (const auto& x : fitTargetGroups(targets)) g += (g.empty() ? "" : ", ") + x;
    return g.empty() ? std::string("none") : g;
  };
  // Starts from nothing when the first item adds, from everything when it removes.
  std::vector<bool> keep(targets.size(), items.front().front() == '!');
  for (const auto& raw : items) {
    const bool remove = raw.front() == '!';
    std::string item = remove ? raw.substr(1) : raw;
    if (item.empty()) throw std::invalid_argument("targets-select: \"" + raw + "\" names nothing");
    bool prefix = item.back() == '*' || item.back() == '-';
    if (item.back() == '*') item.pop_back();
    if (item == "all") prefix = true, item.clear();
    bool matched = false;
    for (std::size_t i = 0; i < targets.size(); ++i) {
      const std::string& id = targets[i].id;
      if (prefix ? id.rfind(item, 0) == 0 : id == item) {
        keep[i] = !remove;
        matched = true;
      }
    }
    if (!matched)
      throw std::invalid_argument("targets-select: \"" + raw + "\" matches no target id (groups: " + groupsText() +
                                  "; a group ends in '-' or '*')");
  }
  std::vector<FitTarget> out;
  for (std::size_t i = 0; i < targets.size(); ++i)
    if (keep[i]) out.push_back(targets[i]);
  if (out.empty()) throw std::invalid_argument("targets-select: \"" + selection + "\" leaves no target");
  return out;
}

std::vector<double> evaluateTargets(const Scene& scene, const std::vector<FitTarget>& targets,
                                    const ObservableSettings& settings) {
  // The targets in parallel over one context (their shared x_p searches and eye boxes are
  // computed once); a failure is reported for the first failing target in file order.
  ObservableContext ctx(scene, settings);
  std::vector<double> out(targets.size());
  std::vector<std::string> errors(targets.size());
  tbb::parallel_for(std::size_t{0}, targets.size(), [&](std::size_t i) {
    const FitTarget& t = targets[i];
    try {
      out[i] = findObservable(t.observable)->evaluate(ctx, t.parameters);
    } catch (const std::exception& e) {
      errors[i] = "target \"" + t.id + "\" (" + t.observable + "): " + e.what();
    }
  });
  for (const auto& e : errors)
    if (!e.empty()) throw std::runtime_error(e);
  return out;
}

}  // namespace fovea

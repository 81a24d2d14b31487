#include "model/analysis/tolerance_run.h"

#include "model/analysis/shard_parts.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <stdexcept>

#include "model/analysis/tolerance_stats.h"
#include "model/analysis/tolerance_trial.h"
#include "model/scene/scene_io.h"

namespace fovea {

TrialRange shardRange(std::uint64_t trials, int k, int n) {
  if (n < 1 || k < 0 || k >= n) throw std::invalid_argument("shard K/N: need 0 <= K < N");
  const auto kk = static_cast<std::uint64_t>(k), nn = static_cast<std::uint64_t>(n);
  return {trials * kk / nn, trials * (kk + 1) / nn};
}

std::string sceneDigest(const Scene& scene) {
  std::uint64_t h = 1469598103934665603ULL;  // FNV-1a 64
  for (const unsigned char c : serializeScene(scene)) h = (h ^ c) * 1099511628211ULL;
  char buf[20];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

std::vector<double> nominalFigures(const Scene& scene, const ToleranceSpec& spec) {
  const FovEvaluator eval = toleranceEvaluator(spec);
  const CompensationTable table = nominalCompensation(scene, spec, eval);
  return runToleranceTrial(scene, spec, eval, std::vector<double>(spec.parameters.size(), 0.0), table);
}

StudyOutcome<std::vector<ToleranceRecord>> runToleranceTrials(const Scene& scene, const ToleranceSpec& spec,
                                                              std::uint64_t seed, TrialRange range,
                                                              const StudyControl& control) {
  const FovEvaluator eval = toleranceEvaluator(spec);
  CompensationTable table;
  if (spec.compensator == Compensator::Fixed) table = nominalCompensation(scene, spec, eval);
  return runSamples<ToleranceRecord>(
      range.end - range.begin,
      [&](std::size_t i) {
        ToleranceRecord r;
        r.trial = range.begin + i;
        r.inputs = trialInputs(spec, seed, r.trial);
        try {
          r.figures = runToleranceTrial(scene, spec, eval, r.inputs, table);
        } catch (const std::invalid_argument& e) {
          r.valid = false;
          r.error = e.what();
          r.figures.assign(toleranceFigureNames().size(), 0.0);
        }
        return r;
      },
      control);
}

bool tolerancePasses(const ToleranceSpec& spec, const ToleranceRecord& r) {
  if (!r.valid) return false;
  const auto& names = toleranceFigureNames();
  for (const auto& [name, b] : spec.pass) {
    const std::size_t f = static_cast<std::size_t>(std::find(names.begin(), names.end(), name) - names.begin());
    const double v = r.figures.at(f);
    if (b.min && !(v >= *b.min)) return false;
    if (b.max && !(v <= *b.max)) return false;
  }
  return true;
}

namespace {

nlohmann::json runHeader(const ToleranceSpec& spec, const ToleranceRunInfo& info) {
  nlohmann::json j;
  j["scene"] = info.scene_name;
  j["scene_digest"] = info.scene_digest;
  j["seed"] = info.seed;
  j["trials"] = info.trials;
  j["spec"] = spec.source;
  j["parameters"] = nlohmann::json::array();
  for (const auto& p : spec.parameters) j["parameters"].push_back(p.name);
  j["figure_names"] = toleranceFigureNames();
  nlohmann::json nominal = nlohmann::json::object();
  for (std::size_t f = 0; f < info.nominal.size(); ++f) nominal[toleranceFigureNames()[f]] = info.nominal[f];
  j["nominal"] = nominal;
  return j;
}

nlohmann::json recordJson(const ToleranceRecord& r) {
  nlohmann::json j{{"trial", r.trial}, {"inputs", r.inputs}, {"figures", r.figures}};
  if (!r.valid) j["error"] = r.error;
  return j;
}

// One number of a record: a JSON number, or null (a non-finite value: the part's writer prints
// NaN and infinities as null), which reads back as NaN and is counted, not binned.
double recordNumber(const nlohmann::json& v, const std::string& where) {
  if (v.is_null()) return std::nan("");
  if (!v.is_number())
    throw std::invalid_argument(where + ": must be a number or null, got " + std::string(v.type_name()));
  return v.get<double>();
}

std::vector<double> recordNumbers(const nlohmann::json& r, const char* key, std::size_t count,
                                  const std::string& where) {
  const std::string at = where + "." + key;
  if (!r.contains(key)) throw std::invalid_argument(at + ": missing");
  const nlohmann::json& a = r[key];
  if (!a.is_array() || a.size() != count)
    throw std::invalid_argument(at + ": must be an array of " + std::to_string(count) + " numbers (one per " +
                                (std::string(key) == "inputs" ? "parameter" : "figure") + " of the spec), got " +
                                (a.is_array() ? std::to_string(a.size()) + " elements" : std::string(a.type_name())));
  std::vector<double> out;
  out.reserve(count);
  for (std::size_t i = 0; i < count; ++i) out.push_back(recordNumber(a[i], at + "[" + std::to_string(i) + "]"));
  return out;
}

// A record of a part, checked against the spec's shape: `where` is "SOURCE: records[i]".
ToleranceRecord recordFrom(const nlohmann::json& j, std::size_t inputs, const std::string& where) {
  if (!j.is_object()) throw std::invalid_argument(where + ": must be an object");
  ToleranceRecord r;
  if (!j.contains("trial") || !j["trial"].is_number_unsigned())
    throw std::invalid_argument(where + ".trial: must be an integer >= 0");
  r.trial = j["trial"].get<std::uint64_t>();
  r.inputs = recordNumbers(j, "inputs", inputs, where);
  r.figures = recordNumbers(j, "figures", toleranceFigureNames().size(), where);
  if (j.contains("error")) {
    if (!j["error"].is_string()) throw std::invalid_argument(where + ".error: must be a string");
    r.valid = false;
    r.error = j["error"].get<std::string>();
  }
  return r;
}

}  // namespace

nlohmann::json tolerancePartJson(const ToleranceSpec& spec, const ToleranceRunInfo& info, int shard, int shards,
                                 const std::vector<ToleranceRecord>& records) {
  nlohmann::json j = runHeader(spec, info);
  j["format"] = "fovea-tolerance-part";
  j["version"] = 1;
  j["shard"] = {shard, shards};
  j["records"] = nlohmann::json::array();
  for (const auto& r : records) j["records"].push_back(recordJson(r));
  return j;
}

nlohmann::json toleranceResultJson(const ToleranceSpec& spec, const ToleranceRunInfo& info,
                                   const std::vector<ToleranceRecord>& records) {
  nlohmann::json j = runHeader(spec, info);
  j["format"] = "fovea-tolerance-result";
  j["version"] = 1;
  j["fov_method"] = "edges";
  j["fov_tolerance_deg"] = spec.fov_tolerance_deg;
  const nlohmann::json stats = toleranceStatistics(spec, info.seed, records);
  for (const auto& [k, v] : stats.items()) j[k] = v;
  nlohmann::json invalid = nlohmann::json::array();
  for (const auto& r : records)
    if (!r.valid) invalid.push_back({{"trial", r.trial}, {"error", r.error}});
  j["invalid_units"] = invalid;
  return j;
}

nlohmann::json mergeToleranceParts(const std::vector<nlohmann::json>& parts, const std::vector<std::string>& sources) {
  const std::map<int, std::size_t> by_shard = indexShardParts(
      parts, "fovea-tolerance-part", {"scene", "scene_digest", "seed", "trials", "spec", "nominal"}, "run", sources);
  const nlohmann::json& h = parts[0];
  const std::string first = shardPartName(sources, 0);
  // The header first: the spec gives the shape every record must have.
  ToleranceSpec spec;
  try {
    spec = parseToleranceSpec(h.at("spec"));
  } catch (const std::exception& e) {
    throw std::invalid_argument(first + ": spec: " + e.what());
  }
  auto unsignedAt = [&](const char* key, std::uint64_t max) {
    // A non-negative integer: a JSON parser gives unsigned, a built document may hold signed.
    const bool whole = h.contains(key) &&
                       (h[key].is_number_unsigned() || (h[key].is_number_integer() && h[key].get<std::int64_t>() >= 0));
    if (!whole || h[key].get<std::uint64_t>() > max)
      throw std::invalid_argument(first + ": " + key + ": must be an integer in [0, " + std::to_string(max) + "]");
    return h[key].get<std::uint64_t>();
  };
  ToleranceRunInfo info;
  info.seed = unsignedAt("seed", std::numeric_limits<std::uint64_t>::max());
  info.trials = unsignedAt("trials", kMaxToleranceTrials);
  if (info.trials < 1)
    throw std::invalid_argument(first + ": trials: must be an integer in [1, " + std::to_string(kMaxToleranceTrials) +
                                "]");
  for (const char* key : {"scene", "scene_digest"})
    if (!h.contains(key) || !h[key].is_string()) throw std::invalid_argument(first + ": " + key + ": must be a string");
  info.scene_name = h["scene"].get<std::string>();
  info.scene_digest = h["scene_digest"].get<std::string>();
  if (!h.contains("nominal") || !h["nominal"].is_object())
    throw std::invalid_argument(first + ": nominal: must be an object");
  for (const auto& name : toleranceFigureNames()) {
    const std::string where = std::string(first).append(": nominal.").append(name);
    if (!h["nominal"].contains(name)) throw std::invalid_argument(where + ": missing");
    info.nominal.push_back(recordNumber(h["nominal"][name], where));
  }
  std::map<std::uint64_t, ToleranceRecord> records;
  for (const auto& [k, i] : by_shard) {
    const nlohmann::json& p = parts[i];
    const std::string where = shardPartName(sources, i);
    const TrialRange range = shardRange(info.trials, k, static_cast<int>(by_shard.size()));
    if (!p.contains("records") || !p["records"].is_array())
      throw std::invalid_argument(where + ": records: must be an array");
    if (p["records"].size() != range.end - range.begin)
      throw std::invalid_argument(where + ": shard " + std::to_string(k) + " is incomplete (" +
                                  std::to_string(p["records"].size()) + " records of " +
                                  std::to_string(range.end - range.begin) + ")");
    for (std::size_t r = 0; r < p["records"].size(); ++r) {
      ToleranceRecord rec =
          recordFrom(p["records"][r], spec.parameters.size(), where + ": records[" + std::to_string(r) + "]");
      if (rec.trial < range.begin || rec.trial >= range.end || records.count(rec.trial))
        throw std::invalid_argument(where + ": trial " + std::to_string(rec.trial) + " out of its shard or repeated");
      records.emplace(rec.trial, std::move(rec));
    }
  }
  std::vector<ToleranceRecord> all;
  all.reserve(records.size());
  for (auto& [t, r] : records) all.push_back(std::move(r));
  return toleranceResultJson(spec, info, all);
}

}  // namespace fovea

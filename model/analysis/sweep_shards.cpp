#include "model/analysis/sweep_shards.h"

#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

#include "model/analysis/analysis_registry.h"
#include "model/analysis/shard_parts.h"
#include "model/analysis/study_analyses.h"
#include "model/analysis/tolerance_run.h"  // shardRange, sceneDigest
#include "model/scene/scene_io.h"

namespace fovea::analysis {

namespace {

// Every field of a sample, so that a merged sweep finishes on the very numbers.
nlohmann::json sampleJson(const GazeSample& s) {
  const FovSample& f = s.fov;
  return {{"gaze_deg", s.gaze_deg},
          {"shift_mm", s.shift_mm},
          {"fov",
           {f.horizontal_deg, f.vertical_deg, f.diagonal_deg, f.extent_horizontal_deg, f.extent_vertical_deg,
            f.mean_efficiency, f.efficiency_uniformity}},
          {"rays_in_pupil", f.rays_in_pupil},
          {"pupil_position_mm", s.pupil_position_mm},
          {"plateau_mm", s.plateau_mm},
          {"best_fov_deg", s.best_fov_deg}};
}

// A finite number at key of sample j, or the message "WHERE.key: problem".
double sampleNumber(const nlohmann::json& j, const char* key, const std::string& where) {
  if (!j.contains(key) || !j[key].is_number() || !std::isfinite(j[key].get<double>()))
    throw std::invalid_argument(where + "." + key + ": must be a finite number");
  return j[key].get<double>();
}

std::vector<double> sampleNumbers(const nlohmann::json& j, const char* key, std::size_t n, const std::string& where) {
  if (!j.contains(key) || !j[key].is_array() || j[key].size() != n)
    throw std::invalid_argument(where + "." + key + ": must be an array of " + std::to_string(n) + " numbers");
  std::vector<double> out;
  for (const auto& v : j[key]) {
    // null: a non-finite figure written by the part's JSON printer (an FOV with no rays).
    if (!v.is_number() && !v.is_null())
      throw std::invalid_argument(where + "." + key + ": must be an array of " + std::to_string(n) + " numbers");
    out.push_back(v.is_null() ? std::nan("") : v.get<double>());
  }
  return out;
}

GazeSample sampleFrom(const nlohmann::json& j, const std::string& where) {
  if (!j.is_object()) throw std::invalid_argument(where + ": must be an object");
  GazeSample s;
  s.gaze_deg = sampleNumber(j, "gaze_deg", where);
  s.shift_mm = sampleNumber(j, "shift_mm", where);
  const auto f = sampleNumbers(j, "fov", 7, where);
  if (!j.contains("rays_in_pupil") || !j["rays_in_pupil"].is_number_integer() ||
      j["rays_in_pupil"].get<long long>() < 0 || j["rays_in_pupil"].get<long long>() > 2147483647)
    throw std::invalid_argument(where + ".rays_in_pupil: must be an integer in [0, 2147483647]");
  s.fov = {f[0], f[1], f[2], f[3], f[4], f[5], f[6], j["rays_in_pupil"].get<int>()};
  s.pupil_position_mm = sampleNumber(j, "pupil_position_mm", where);
  const auto plateau = sampleNumbers(j, "plateau_mm", 2, where);
  s.plateau_mm = {plateau[0], plateau[1]};
  s.best_fov_deg = sampleNumber(j, "best_fov_deg", where);
  return s;
}

const AnalysisDefinition& sweepDefinition() {
  const AnalysisDefinition* d = findAnalysisDefinition("sweep");
  if (!d) throw std::logic_error("the sweep analysis is not registered");
  return *d;
}

}  // namespace

std::optional<nlohmann::json> sweepPartJson(const Scene& scene, const nlohmann::json& values, int shard, int shards,
                                            const StudyControl& control) {
  const std::vector<double> gazes =
      sweepGazes(numberOf(values, "gaze-from"), numberOf(values, "gaze-to"), numberOf(values, "gaze-step"));
  const TrialRange range = shardRange(gazes.size(), shard, shards);
  const std::size_t count = range.end - range.begin + (shard == 0 ? 1 : 0);  // shard 0: + the reference
  const FovEvaluator eval = evaluatorFrom(values);
  const GazeStudyOptions options = gazeStudyOptionsFrom(values);
  auto runs = runSamples<GazeSample>(
      count,
      [&](std::size_t i) {
        const double g = range.begin + i < range.end ? gazes[range.begin + i] : 0.0;
        return optimiseShift(scene, eval, g, axisFrom(values), sweepMethodFrom(values), options);
      },
      control);
  if (!runs.ok()) return std::nullopt;
  nlohmann::json j;
  j["format"] = "fovea-sweep-part";
  j["version"] = 1;
  j["shard"] = {shard, shards};
  j["values"] = values;
  j["scene_digest"] = sceneDigest(scene);
  j["scene"] = serializeScene(scene);  // the file's text: parseScene(serializeScene(s)) == s
  j["gaze_count"] = gazes.size();
  j["first_gaze"] = range.begin;
  j["samples"] = nlohmann::json::array();
  for (std::size_t i = 0; range.begin + i < range.end; ++i) j["samples"].push_back(sampleJson((*runs.value)[i]));
  if (shard == 0) j["reference"] = sampleJson(runs.value->back());
  return j;
}

std::optional<nlohmann::json> mergeSweepParts(const std::vector<nlohmann::json>& parts, const StudyControl& control,
                                              const std::vector<std::string>& sources) {
  const std::map<int, std::size_t> index =
      indexShardParts(parts, "fovea-sweep-part", {"values", "scene_digest", "scene", "gaze_count"}, "sweep", sources);
  const std::string first = shardPartName(sources, 0);
  // The header: the values the sweep was run with, and the gazes they give.
  if (!parts[0].contains("values") || !parts[0]["values"].is_object())
    throw std::invalid_argument(first + ": values: must be an object");
  nlohmann::json values = parts[0]["values"];
  const AnalysisDefinition& def = sweepDefinition();
  const auto problems = validateValues(def, values);
  if (!problems.empty()) throw std::invalid_argument(first + ": values: " + problems.front().text());
  const std::vector<double> gazes =
      sweepGazes(numberOf(values, "gaze-from"), numberOf(values, "gaze-to"), numberOf(values, "gaze-step"));
  if (!parts[0]["gaze_count"].is_number_unsigned() || parts[0]["gaze_count"].get<std::uint64_t>() != gazes.size())
    throw std::invalid_argument(first + ": gaze_count: must be " + std::to_string(gazes.size()) +
                                " (the gazes of its values' gaze-from, gaze-to and gaze-step), got " +
                                parts[0]["gaze_count"].dump());
  std::map<int, const nlohmann::json*> by_shard;
  for (const auto& [k, i] : index) {
    const nlohmann::json& p = parts[i];
    const std::string where = shardPartName(sources, i);
    const TrialRange range = shardRange(gazes.size(), k, static_cast<int>(index.size()));
    if (!p.contains("first_gaze") || !p["first_gaze"].is_number_unsigned() ||
        p["first_gaze"].get<std::uint64_t>() != range.begin || !p.contains("samples") || !p["samples"].is_array() ||
        p["samples"].size() != range.end - range.begin || (k == 0 && !p.contains("reference")))
      throw std::invalid_argument(where + ": shard " + std::to_string(k) + " is incomplete");
    by_shard[k] = &p;
  }

  if (!parts[0]["scene"].is_string()) throw std::invalid_argument(first + ": scene: must be a scene file's text");
  SceneLoadResult loaded = parseScene(parts[0]["scene"].get<std::string>(), "the parts' scene");
  if (!loaded.ok() || !parts[0]["scene_digest"].is_string() ||
      sceneDigest(*loaded.scene) != parts[0]["scene_digest"].get<std::string>())
    throw std::invalid_argument(first + ": scene: does not match its digest");
  std::vector<GazeSample> samples;
  GazeSample reference;
  for (const auto& [k, p] : by_shard) {
    const std::string where = shardPartName(sources, index.at(k));
    const std::size_t begin = shardRange(gazes.size(), k, static_cast<int>(index.size())).begin;
    for (std::size_t j = 0; j < (*p)["samples"].size(); ++j) {
      const std::string at = where + ": samples[" + std::to_string(j) + "]";
      samples.push_back(sampleFrom((*p)["samples"][j], at));
      // A sample's gaze is the one its position in the run gives (to the digits JSON keeps).
      const double expected = gazes[begin + j];
      if (!(std::abs(samples.back().gaze_deg - expected) <= 1e-9 * std::max(1.0, std::abs(expected))))
        throw std::invalid_argument(at + ".gaze_deg: must be " + formatNumber(expected) + " (gaze " +
                                    std::to_string(begin + j) + " of the run), got " +
                                    formatNumber(samples.back().gaze_deg));
    }
  }
  reference = sampleFrom((*by_shard[0])["reference"], shardPartName(sources, index.at(0)) + ": reference");
  if (reference.gaze_deg != 0.0)
    throw std::invalid_argument(shardPartName(sources, index.at(0)) + ": reference.gaze_deg: must be 0");
  const auto r = finishSweep(*loaded.scene, evaluatorFrom(values), std::move(samples), reference, axisFrom(values),
                             sweepMethodFrom(values), gazeStudyOptionsFrom(values), control);
  if (!r.ok()) return std::nullopt;
  return sweepDocument(*r.value, values);
}

}  // namespace fovea::analysis

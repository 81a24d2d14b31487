#include "model/analysis/sweep_shards.h"

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

GazeSample sampleFrom(const nlohmann::json& j) {
  GazeSample s;
  s.gaze_deg = j.at("gaze_deg").get<double>();
  s.shift_mm = j.at("shift_mm").get<double>();
  const auto f = j.at("fov").get<std::vector<double>>();
  if (f.size() != 7) throw std::invalid_argument("bad sample");
  s.fov = {f[0], f[1], f[2], f[3], f[4], f[5], f[6], j.at("rays_in_pupil").get<int>()};
  s.pupil_position_mm = j.at("pupil_position_mm").get<double>();
  s.plateau_mm = j.at("plateau_mm").get<std::array<double, 2>>();
  s.best_fov_deg = j.at("best_fov_deg").get<double>();
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

std::optional<nlohmann::json> mergeSweepParts(const std::vector<nlohmann::json>& parts, const StudyControl& control) {
  const std::map<int, std::size_t> index =
      indexShardParts(parts, "fovea-sweep-part", {"values", "scene_digest", "scene", "gaze_count"}, "sweep");
  std::map<int, const nlohmann::json*> by_shard;
  for (const auto& [k, i] : index) {
    const nlohmann::json& p = parts[i];
    const TrialRange range = shardRange(p.at("gaze_count").get<std::uint64_t>(), k, static_cast<int>(index.size()));
    if (p.at("first_gaze").get<std::uint64_t>() != range.begin || p.at("samples").size() != range.end - range.begin ||
        (k == 0 && !p.contains("reference")))
      throw std::invalid_argument("merge: part " + std::to_string(i + 1) + ": shard " + std::to_string(k) +
                                  " is incomplete");
    by_shard[k] = &p;
  }

  nlohmann::json values = parts[0]["values"];
  const AnalysisDefinition& def = sweepDefinition();
  const auto problems = validateValues(def, values);
  if (!problems.empty()) throw std::invalid_argument("merge: the parts' sweep values: " + problems.front().text());
  if (!parts[0]["scene"].is_string())
    throw std::invalid_argument("merge: part 1: \"scene\" is not a scene file's text");
  SceneLoadResult loaded = parseScene(parts[0]["scene"].get<std::string>(), "the parts' scene");
  if (!loaded.ok() || sceneDigest(*loaded.scene) != parts[0]["scene_digest"].get<std::string>())
    throw std::invalid_argument("merge: the parts' scene does not match its digest");
  std::vector<GazeSample> samples;
  GazeSample reference;
  try {
    for (const auto& [k, p] : by_shard)
      for (const auto& s : (*p)["samples"]) samples.push_back(sampleFrom(s));
    reference = sampleFrom((*by_shard[0])["reference"]);
  } catch (const std::exception& e) {
    throw std::invalid_argument(std::string("merge: a malformed sample (") + e.what() + ")");
  }
  const auto r = finishSweep(*loaded.scene, evaluatorFrom(values), std::move(samples), reference, axisFrom(values),
                             sweepMethodFrom(values), gazeStudyOptionsFrom(values), control);
  if (!r.ok()) return std::nullopt;
  return sweepDocument(*r.value, values);
}

}  // namespace fovea::analysis

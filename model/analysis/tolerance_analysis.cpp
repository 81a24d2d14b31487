#include "model/analysis/tolerance_analysis.h"

#include <cstdint>
#include <stdexcept>
#include <string>

#include "model/analysis/tolerance_run.h"
#include "model/analysis/tolerance_spec.h"
#include "model/io/json_input.h"

namespace fovea::analysis {

namespace {

constexpr const char* kOverrides[] = {"gaze-from", "gaze-to", "gaze-step"};

bool hasOverride(const nlohmann::json& v) {
  if (v.contains("compensator") && v["compensator"].is_string() && v["compensator"] != "spec") return true;
  for (const char* k : kOverrides)
    if (v.contains(k) && !v[k].is_null()) return true;
  return false;
}

}  // namespace

std::string_view defaultToleranceSpecText() {
  static constexpr std::string_view kJson =
#include "fovea/default_tolerance_spec.inc"
      ;
  return kJson;
}

nlohmann::json toleranceSpecDocument(const nlohmann::json& v) {
  nlohmann::json doc;
  const bool file = v.contains("spec") && v["spec"].is_string();
  if (file) {
    try {
      doc = readJsonFile(v["spec"].get<std::string>());
    } catch (const std::exception& e) {
      throw std::invalid_argument(std::string("spec: ") + e.what());
    }
  } else {
    auto parsed = parseJsonText(defaultToleranceSpecText());
    if (auto* e = std::get_if<JsonInputError>(&parsed)) throw std::runtime_error("the default spec: " + e->reason);
    doc = std::get<nlohmann::json>(parsed);
  }
  if (!doc.is_object()) throw std::invalid_argument("spec: not a JSON object");
  if (v.contains("compensator") && v["compensator"].is_string() && v["compensator"] != "spec")
    doc["compensator"] = v["compensator"];
  const char* keys[] = {"from_deg", "to_deg", "step_deg"};
  for (int i = 0; i < 3; ++i)
    if (v.contains(kOverrides[i]) && !v[kOverrides[i]].is_null()) {
      if (!doc.contains("gaze") || !doc["gaze"].is_object()) doc["gaze"] = nlohmann::json::object();
      doc["gaze"][keys[i]] = v[kOverrides[i]];
    }
  return doc;
}

AnalysisDefinition toleranceAnalysis() {
  AnalysisDefinition d;
  d.id = "tolerance";
  d.title = "Tolerance: yield, distributions, sensitivity";
  d.description =
      "Monte Carlo tolerancing: built units drawn from the spec's tolerances, each run through the gaze range "
      "with its compensator; yield against the pass criterion, the distribution of every figure and the "
      "variance-based sensitivity ranking (docs/tolerancing.md).";
  d.parameters = {
      filePath("spec", "Spec file", "the shipped prototype spec (resources/tolerance/prototype-tolerance.json)",
               "tolerance spec (JSON, docs/tolerancing.md)"),
      integer("trials", "Trials", 100, 1, 1000000, "number of trials (Saltelli blocks of parameters + 2)"),
      integer("seed", "Seed", 1, 0, 2147483647, "random seed; trial i depends only on (seed, i)"),
      choice("compensator", "Compensator", {"spec", "refind", "fixed"}, "spec",
             "spec: as the spec file says; refind: x_p re-found per gaze on each unit; fixed: the nominal x_p table"),
      gazeAngle("gaze-from", "Gaze from", nullptr, "first gaze of every unit"),
      gazeAngle("gaze-to", "Gaze to", nullptr, "last gaze of every unit"),
      number("gaze-step", "Gaze step", "deg", nullptr, 0.0, 2 * kGazeLimitDeg, 2, "gaze step (> 0)"),
  };
  for (auto& p : d.parameters)
    if (p.name == "compensator" || p.name.rfind("gaze-", 0) == 0) {
      p.studio_only = true;
      if (p.default_value.is_null()) p.unset_meaning = "the spec's";
    }
  d.parameters.back().minimum_exclusive = true;
  d.plots = {"tolerance-yield", "tolerance-ranking"};
  for (const auto& f : toleranceFigureNames()) d.plots.push_back("tolerance-" + f);
  d.cli_generated = false;  // cmd_tolerance.cpp: --spec (required), --trials, --seed, shards, Slurm
  d.cli_unavailable = [](const nlohmann::json& v) -> std::optional<std::string> {
    if (!v.contains("spec") || !v["spec"].is_string())
      return std::string(
          "Choose a spec file first: fovea-cli tolerance needs --spec (the studio's default is built in).");
    if (hasOverride(v))
      return std::string(
          "The compensator and gaze overrides are studio only: write them into the spec file for fovea-cli.");
    return std::nullopt;
  };
  d.run = [](const Scene& scene, const nlohmann::json& v,
             const StudyControl& control) -> std::optional<nlohmann::json> {
    const nlohmann::json doc = toleranceSpecDocument(v);
    const std::string source = v.contains("spec") && v["spec"].is_string() ? v["spec"].get<std::string>()
                                                                           : std::string("the default tolerance spec");
    const ToleranceSpec spec = parseToleranceSpec(doc, source);
    checkToleranceSpecPaths(spec, scene, source);
    ToleranceRunInfo info;
    info.scene_name = scene.name;
    info.scene_digest = sceneDigest(scene);
    info.seed = static_cast<std::uint64_t>(integerOf(v, "seed"));
    info.trials = static_cast<std::uint64_t>(integerOf(v, "trials"));
    info.nominal = nominalFigures(scene, spec);
    if (control.cancelled()) return std::nullopt;
    const auto run = runToleranceTrials(scene, spec, info.seed, {0, info.trials}, control);
    if (!run.ok()) return std::nullopt;
    return toleranceResultJson(spec, info, *run.value);
  };
  return d;
}

}  // namespace fovea::analysis

#include "model/analysis/fit_analysis.h"

#include <climits>
#include <sstream>
#include <stdexcept>

#include "model/analysis/fit_json.h"
#include "model/analysis/fit_solver.h"
#include "model/io/json_input.h"
#include "model/scene/scene_parameters.h"

namespace fovea::analysis {

std::vector<std::string> splitFreeSpecs(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

Scene sceneWithFittedValues(const Scene& scene, const nlohmann::json& doc) {
  Scene out = scene;
  for (const auto& p : doc.at("parameters"))
    out = withParameter(out, p.at("path").get<std::string>(), p.at("fitted").get<double>());
  return out;
}

AnalysisDefinition fitAnalysis() {
  AnalysisDefinition d;
  d.id = "fit";
  d.title = "Fit to measurements";
  d.description =
      "Fits chosen scene numbers to target observables with uncertainties (a targets file, docs/fitting.md): NLopt "
      "BOBYQA on the normalised residuals from several starts; fitted values, residuals, uncertainties and "
      "correlations from the Jacobian, warnings for parameters the targets cannot determine.";
  ParameterSpec targets = text("targets", "Targets file", {}, "", "targets JSON file (fovea-fit-targets)");
  targets.default_value = nullptr;
  targets.unset_meaning = "choose a targets file";
  ParameterSpec free = text("free", "Free parameters",
                            {"eye.relief_mm", "hoe_layers[1].n1", "hoe_layers[1].shrinkage_percent",
                             "projector.position_mm[0]=85:95", "hoe.rotation_deg[0]=+-2"},
                            "", "scene paths to fit, separated by spaces: PATH, PATH=LO:HI or PATH=+-D");
  free.default_value = nullptr;
  free.unset_meaning = "choose the parameters to fit";
  ParameterSpec select = text("targets-select", "Targets used", {"sim-", "meas-", "all"}, "",
                              "which targets to fit: ids or groups ending in '-' (sim-, meas-), separated by commas; "
                              "'!' removes; unset: all");
  select.default_value = nullptr;  // unset: every target (an empty text is no valid value)
  select.unset_meaning = "all targets";
  d.parameters = {targets,
                  free,
                  select,
                  integer("starts", "Starts", 3, 1, 50, "optimiser starts: the scene's values, then random ones"),
                  integer("seed", "Seed", 1, 0, INT_MAX, "seed of the random starts"),
                  integer("max-evals", "Max evaluations", 0, 0, 1000000, "per start; 0: 40 (n + 2)")};
  d.plots = {"fit-residuals"};
  d.cli_generated = false;
  d.run = [](const Scene& scene, const nlohmann::json& v,
             const StudyControl& control) -> std::optional<nlohmann::json> {
    if (v.at("targets").is_null()) throw std::invalid_argument("targets: choose a targets file");
    if (v.at("free").is_null()) throw std::invalid_argument("free: choose at least one parameter to fit");
    const std::string path = textOf(v, "targets");
    const nlohmann::json file = readJsonFile(path);  // its errors name the file
    std::vector<FitTarget> t;
    try {
      t = parseFitTargets(file);
    } catch (const std::invalid_argument& e) {
      throw std::runtime_error(path + ": " + e.what());
    }
    const std::string selection = v.at("targets-select").is_null() ? std::string() : textOf(v, "targets-select");
    t = selectFitTargets(t, selection);  // its errors name the item and the file's groups
    std::vector<FreeParameter> free_parameters;
    try {
      free_parameters = parseFreeParameters(scene, splitFreeSpecs(textOf(v, "free")));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("free: ") + e.what());
    }
    FitOptions o;
    o.starts = integerOf(v, "starts");
    o.seed = static_cast<std::uint64_t>(integerOf(v, "seed"));
    o.max_evaluations = integerOf(v, "max-evals");
    const auto r = fitScene(scene, t, free_parameters, o, control);
    if (!r.ok()) return std::nullopt;
    nlohmann::json out = fitResultJson(*r.value, o);
    out["targets_file"] = path;
    out["targets_select"] = selection;
    out["targets_available"] = file.is_object() ? file["targets"].size() : file.size();
    return out;
  };
  return d;
}

}  // namespace fovea::analysis

#include "model/analysis/analysis_registry.h"

#include <stdexcept>

#include "model/analysis/fit_analysis.h"
#include "model/analysis/study_analyses.h"
#include "model/analysis/tolerance_analysis.h"

namespace fovea::analysis {

const ParameterSpec* AnalysisDefinition::parameter(std::string_view name) const {
  for (const auto& p : parameters)
    if (p.name == name) return &p;
  return nullptr;
}

const OptionGroup* AnalysisDefinition::groupOf(std::string_view parameter_name) const {
  for (const auto& g : option_groups)
    for (const auto& m : g.members)
      if (m == parameter_name) return &g;
  return nullptr;
}

namespace {
// The registry: one line per analysis, in the order the studio lists them.
std::vector<AnalysisDefinition> buildRegistry() {
  return {traceAnalysis(),          sweepAnalysis(),        compareShiftAnalysis(), sensitivityAnalysis(),
          resolutionAnalysis(),     optimizeLensAnalysis(), selectivityAnalysis(),  gratingSweepAnalysis(),
          kogelnikVsRcwaAnalysis(), toleranceAnalysis(),    fitAnalysis()};
}
}  // namespace

const std::vector<AnalysisDefinition>& analysisRegistry() {
  static const std::vector<AnalysisDefinition> registry = buildRegistry();
  return registry;
}

const AnalysisDefinition* findAnalysisDefinition(std::string_view id) {
  for (const auto& d : analysisRegistry())
    if (d.id == id) return &d;
  return nullptr;
}

nlohmann::json defaultValues(const AnalysisDefinition& def) {
  nlohmann::json v = nlohmann::json::object();
  for (const auto& p : def.parameters) v[p.name] = p.default_value;
  return v;
}

std::vector<ParameterProblem> validateValues(const AnalysisDefinition& def, nlohmann::json& values) {
  std::vector<ParameterProblem> problems;
  if (!values.is_object()) values = nlohmann::json::object();
  for (const auto& [name, value] : values.items())
    if (!def.parameter(name)) problems.push_back({name, "no such parameter of " + def.id});
  for (const auto& p : def.parameters) {
    if (!values.contains(p.name)) values[p.name] = p.default_value;
    if (auto e = validateValue(p, values[p.name])) problems.push_back({p.name, *e});
  }
  if (problems.empty() && def.check)
    if (auto e = def.check(values)) problems.push_back(*e);
  return problems;
}

std::optional<nlohmann::json> runAnalysis(const AnalysisDefinition& def, const Scene& scene, nlohmann::json values,
                                          const StudyControl& control) {
  const auto problems = validateValues(def, values);
  if (!problems.empty()) {
    std::string all;
    for (const auto& p : problems) all += (all.empty() ? "" : "; ") + p.text();
    throw std::invalid_argument(all);
  }
  return def.run(scene, values, control);
}

}  // namespace fovea::analysis

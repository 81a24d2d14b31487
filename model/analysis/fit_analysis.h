#pragma once
// The "fit" analysis of the registry (fovea-cli fit, the studio's "Fit to measurements"):
// docs/fitting.md. Its free parameters travel as one text value (specs separated by spaces)
// because the registry's parameters are scalars; fovea-cli fit's command line is written by
// hand (--free takes several values) with the same option names.

#include <string>
#include <vector>

#include "model/analysis/analysis_registry.h"
#include "model/analysis/fit_parameters.h"

namespace fovea::analysis {

AnalysisDefinition fitAnalysis();

// "a=1:2  b" -> {"a=1:2", "b"}.
std::vector<std::string> splitFreeSpecs(const std::string& text);

// The scene with the fitted values of a fit document (its "parameters": path, fitted).
Scene sceneWithFittedValues(const Scene& scene, const nlohmann::json& fit_document);

}  // namespace fovea::analysis

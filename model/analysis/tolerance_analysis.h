#pragma once
// The "tolerance" analysis of the registry (analysis_registry.h): the Monte Carlo tolerancing
// of tolerance_run.h for the studio's Analyses panel, with the same document as
// `fovea-cli tolerance SCENE --spec TOL.json --trials N --seed S --json` (docs/tolerancing.md).
// The command is written by hand (cmd_tolerance.cpp: shards, Slurm); its --spec, --trials and
// --seed are this definition's parameters. With no spec file the shipped default
// (resources/tolerance/prototype-tolerance.json, compiled in) is used. The studio may also
// override the spec's compensator and gaze range (studio only: the CLI reads them from the spec
// file, so "Copy CLI" refuses while an override is set).

#include <string_view>

#include <nlohmann/json.hpp>

#include "model/analysis/analysis_registry.h"

namespace fovea::analysis {

AnalysisDefinition toleranceAnalysis();

// The shipped default spec (resources/tolerance/prototype-tolerance.json) as text.
std::string_view defaultToleranceSpecText();

// The spec document the values select: the file of "spec" (or the default), with the studio's
// overrides ("compensator", "gaze-from", "gaze-to", "gaze-step") written into it. Throws
// std::invalid_argument naming the file and the problem.
nlohmann::json toleranceSpecDocument(const nlohmann::json& values);

}  // namespace fovea::analysis

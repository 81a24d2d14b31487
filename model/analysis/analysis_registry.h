#pragma once
// The analysis registry: every analysis of fovea-cli and the studio's Analyses panel,
// declared once — its id (the fovea-cli subcommand), title, typed parameters (name, unit,
// default, range, help: analysis_parameters.h) and run function. fovea-cli's subcommand
// options (app/cli/analysis_options.h) and the studio's forms, defaults, validation and
// "Copy CLI" (widgets/analyses/analysis_catalog.h) are generated from it, so both sides
// have one default and one validator by construction.
//
// How to add an analysis
// ----------------------
// 1. Write the study in model/ (pure C++, StudyControl for progress and cancel) and its
//    JSON document (analysis_json.h), if it does not exist yet.
// 2. Add one definition to the list in analysis_registry.cpp (or a function returning an
//    AnalysisDefinition in its own file, called from that list):
//      AnalysisDefinition d;
//      d.id = "my-study";                      // also the fovea-cli subcommand
//      d.title = "My study";  d.description = "What it computes (seed section).";
//      d.parameters = {positive("step-deg", "Step", "deg", 0.5, 10, 2, "sample step"),
//                      integer("samples", "Samples", 101, 3, 10001, "samples per curve")};
//      d.plots = {"my-plot"};                  // plot ids it feeds (widgets/plots)
//      d.run = [](const Scene& s, const nlohmann::json& v, const StudyControl& c)
//          -> std::optional<nlohmann::json> { return myStudyJson(myStudy(s, numberOf(v, "step-deg"), c)); };
//    The studio lists it at once (form, defaults, validation, Run, Copy CLI).
// 3. For the command line, add app/cli/cmd_my_study.cpp: `addAnalysisOptions(cmd, def)`
//    creates every option from the definition; the callback calls `parameterValues()`
//    (validated, exit 2 naming the flag) and `def.run(...)`, then prints the JSON.
// Parameters given on the command line as one comma list ("--gaze-deg YAW[,PITCH]") are
// declared as scalar parameters plus an OptionGroup. Values are a JSON object
// {name: value}; runAnalysis() validates before running.

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "model/analysis/analysis_parameters.h"
#include "model/analysis/study_runner.h"
#include "model/scene/scene.h"

namespace fovea::analysis {

// Scalar parameters that fovea-cli takes as one comma-separated option: "--gaze-deg 10,2"
// sets gaze-yaw 10 and gaze-pitch 2; trailing members left out are 0 ("--gaze-deg 10").
struct OptionGroup {
  std::string flag;                  // without dashes: "gaze-deg"
  std::vector<std::string> members;  // parameter names, in order
  std::string help;
  bool repeatable = false;  // the command takes it several times (one result per occurrence)
};

using RunFunction =
    std::function<std::optional<nlohmann::json>(const Scene&, const nlohmann::json& values, const StudyControl&)>;

struct AnalysisDefinition {
  std::string id;  // the fovea-cli subcommand
  std::string title, description;
  std::vector<ParameterSpec> parameters;
  std::vector<OptionGroup> option_groups;
  std::vector<std::string> plots;  // ids of the plots its result feeds (widgets/plots/plot_builders.h)
  // fovea-cli's subcommand `id` takes these options (but the studio_only ones): "Copy CLI".
  bool cli_twin = true;
  // ... and they are generated from this definition (app/cli/analysis_options.h). False: the
  // command is written by hand with the same option names.
  bool cli_generated = true;
  bool takes_scene = true;  // the command's first argument is the scene file
  // Why these values have no equivalent command line (a required file not chosen, a studio-only
  // override set), or nothing when "Copy CLI" can write one.
  std::function<std::optional<std::string>(const nlohmann::json& values)> cli_unavailable;
  bool cached = false;  // results are kept in StudyCache (expensive studies)
  // A check across parameters (ranges that depend on each other), after each value is valid.
  std::function<std::optional<ParameterProblem>(const nlohmann::json& values)> check;
  // Computes the analysis from validated values; nothing when cancelled. Throws
  // std::invalid_argument (bad parameter for this scene) or std::runtime_error.
  RunFunction run;

  const ParameterSpec* parameter(std::string_view name) const;
  const OptionGroup* groupOf(std::string_view parameter_name) const;
};

const std::vector<AnalysisDefinition>& analysisRegistry();
const AnalysisDefinition* findAnalysisDefinition(std::string_view id);

// Every parameter at its default (null for unset ones).
nlohmann::json defaultValues(const AnalysisDefinition& def);
// Fills missing parameters with their defaults, validates each (validateValue) and then the
// definition's cross check; returns every problem. Unknown names are problems too.
std::vector<ParameterProblem> validateValues(const AnalysisDefinition& def, nlohmann::json& values);

// Validates (std::invalid_argument with every problem, "gaze-step: must be > 0 ...") and runs.
std::optional<nlohmann::json> runAnalysis(const AnalysisDefinition& def, const Scene& scene, nlohmann::json values,
                                          const StudyControl& control = {});

}  // namespace fovea::analysis

#pragma once
// fovea-cli options generated from the analysis registry (model/analysis/analysis_registry.h):
// one CLI11 option per parameter ("--gaze-step"), one per option group ("--gaze-deg
// YAW[,PITCH]"), with the registry's help, unit, default and range. Values are read as text
// and checked by the registry's validator (analysis_parameters.h), so "nan", "inf" and
// out-of-range numbers are refused with exit 2 and a message naming the flag, before any work.

#include <map>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "model/analysis/analysis_registry.h"

namespace fovea::cli {

class AnalysisOptions {
 public:
  AnalysisOptions(CLI::App* cmd, const analysis::AnalysisDefinition& def);

  // The parameter values of the parsed command line (defaults for options not given),
  // validated; throws CliError(2) naming every offending flag. A repeatable group takes its
  // first occurrence.
  nlohmann::json values() const;
  // One validated value set per occurrence of the repeatable group `flag` (one set with the
  // group unset when the flag was not given).
  std::vector<nlohmann::json> valuesPerOccurrence(const std::string& flag) const;
  const analysis::AnalysisDefinition& definition() const { return def_; }

 private:
  nlohmann::json collect(const std::string& occurrence_flag, std::size_t occurrence) const;

  CLI::App* cmd_;
  const analysis::AnalysisDefinition& def_;
  std::map<std::string, std::string> scalars_;              // parameter name -> text given
  std::map<std::string, std::vector<std::string>> groups_;  // group flag -> texts given
};

// Adds the options of registered analysis `id` to `cmd` (which must outlive the result).
std::shared_ptr<AnalysisOptions> addAnalysisOptions(CLI::App* cmd, const std::string& id);

// A hand-written command's numeric option checked by the same validator (finite, range,
// whole number): CLI11 refuses a bad value with "--flag: problem" (exit 2).
CLI::Option* addCheckedOption(CLI::App* cmd, const std::string& flag, double& target,
                              const analysis::ParameterSpec& spec);
CLI::Option* addCheckedOption(CLI::App* cmd, const std::string& flag, int& target, const analysis::ParameterSpec& spec);

// "first gaze angle (deg, default -20; must lie in [-80, 80] deg)"
std::string optionHelp(const analysis::ParameterSpec& spec);

}  // namespace fovea::cli

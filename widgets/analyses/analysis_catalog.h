#pragma once
// The studio's view of the analysis registry (model/analysis/analysis_registry.h): every
// analysis with its parameters in Qt types for the Analyses panel's form, and the form's
// defaults, validation, "Copy CLI" command line and run — all generated from the registry,
// so they match fovea-cli's options by construction (tests/gui/tst_analysis_defaults.cpp).

#include <QList>
#include <QString>
#include <QStringList>
#include <QVariant>
#include <QVariantMap>

#include <optional>

#include <nlohmann/json.hpp>

#include "model/analysis/analysis_registry.h"
#include "model/analysis/study_runner.h"
#include "model/scene/scene.h"

namespace fovea::widgets {

struct AnalysisParameter {
  enum class Kind { Number, Integer, Choice, Text, FilePath };
  QString key;  // the fovea-cli flag without dashes ("gaze-from")
  QString label;
  QString unit;
  Kind kind = Kind::Number;
  QVariant defaultValue;  // invalid (null) = unset: `unsetMeaning` ("the scene's gaze")
  double minimum = -1e9, maximum = 1e9;
  int decimals = 3;
  QStringList choices;  // Choice: the allowed values; Text: suggestions (editable)
  QString help;
  QString unsetMeaning;
};

struct AnalysisSpec {
  QString id;  // the fovea-cli command
  QString title;
  QString description;
  QList<AnalysisParameter> parameters;
  QStringList plots;  // ids of the plots its result feeds (plot_builders.h)
  bool hasCliTwin = true;
  const analysis::AnalysisDefinition* definition = nullptr;
};

using AnalysisParams = QVariantMap;

const QList<AnalysisSpec>& analysisCatalog();
const AnalysisSpec* findAnalysis(const QString& id);

// Every parameter at its registry default (an invalid QVariant for unset ones).
// `raysOverride` > 0 replaces the "rays" default (the report dialog's ray count).
AnalysisParams defaultParameters(const AnalysisSpec& spec, int raysOverride = 0);
// Fills missing keys with defaults and checks every value with the registry's validator;
// returns the problems ("gaze-step: must be > 0 and <= 90 deg, got 0").
QStringList validateParameters(const AnalysisSpec& spec, AnalysisParams& params);

// The equivalent shell command ("fovea-cli sweep bench.json --gaze-from -20 ... --json").
// Empty when the analysis has no fovea-cli twin or, for an analysis of a scene, when
// `scenePath` is empty (fovea-cli reads the scene from its file: save it first).
QString cliCommandLine(const AnalysisSpec& spec, const AnalysisParams& params, const QString& scenePath);

// Why the values have no equivalent command line (the registry's cli_unavailable: a required
// file not chosen, a studio-only override set); empty when they have one.
QString cliUnavailableReason(const AnalysisSpec& spec, const AnalysisParams& params);

// Computes the analysis. Throws std::invalid_argument (bad parameter) or std::runtime_error
// (cannot be computed for this scene). Returns nothing when cancelled through `control`.
// Cached studies (the registry's `cached`) are returned from StudyCache::global() when
// scene and parameters match; the result then has "cached": true.
std::optional<nlohmann::json> runAnalysis(const QString& id, const Scene& scene, const AnalysisParams& params,
                                          const StudyControl& control = {});

// The parameters as the registry's JSON values and back.
nlohmann::json parameterValues(const AnalysisSpec& spec, const AnalysisParams& params);
AnalysisParams fromParameterValues(const nlohmann::json& values);

}  // namespace fovea::widgets

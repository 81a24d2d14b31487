#pragma once
// Every analysis the studio can run, with the parameters of its fovea-cli twin (same names,
// same defaults, same JSON result keys: model/analysis/analysis_json.h). The analyses panel
// builds its form from these specs; runAnalysis() computes one on the calling thread (the
// panel calls it from a worker thread) with progress and cancellation through StudyControl.
//
// Analyses and their twins: trace, sweep, compare-shift, sensitivity, resolution,
// optimize-lens, selectivity (`fovea-cli <id>`); grating = `fovea-cli grating` swept over the
// probe angle (optionally against RCWA); kogelnik-vs-rcwa = the error/time map of
// docs/benchmarks.md (benchmarks/bench_rcwa.cpp).

#include <QList>
#include <QString>
#include <QStringList>
#include <QVariant>
#include <QVariantMap>

#include <optional>

#include <nlohmann/json.hpp>

#include "model/analysis/study_runner.h"
#include "model/scene/scene.h"

namespace fovea::widgets {

struct AnalysisParameter {
  enum class Kind { Number, Integer, Choice, Text };
  QString key;  // the fovea-cli flag without dashes ("gaze-from"); "SCENE" style args never appear
  QString label;
  QString unit;
  Kind kind = Kind::Number;
  QVariant defaultValue;
  double minimum = -1e9, maximum = 1e9;
  int decimals = 3;
  QStringList choices;  // Choice: the allowed values; Text: suggestions (editable)
  QString help;
};

struct AnalysisSpec {
  QString id;  // the fovea-cli command
  QString title;
  QString description;
  QList<AnalysisParameter> parameters;
  QStringList plots;  // ids of the plots its result feeds (plot_builders.h)
  bool hasCliTwin = true;
};

using AnalysisParams = QVariantMap;

const QList<AnalysisSpec>& analysisCatalog();
const AnalysisSpec* findAnalysis(const QString& id);

// Every parameter at its default. `defaultRays` (Preferences) replaces the "rays" default.
AnalysisParams defaultParameters(const AnalysisSpec& spec, int defaultRays = 0);
// Fills missing keys with defaults and checks every value against its kind and range;
// returns the problems ("gaze-step: must be > 0").
QStringList validateParameters(const AnalysisSpec& spec, AnalysisParams& params);

// The equivalent shell command ("fovea-cli sweep bench.json --gaze-from -20 ... --json").
QString cliCommandLine(const AnalysisSpec& spec, const AnalysisParams& params, const QString& scenePath);

// Computes the analysis. Throws std::invalid_argument (bad parameter) or std::runtime_error
// (cannot be computed for this scene). Returns nothing when cancelled through `control`.
// Studies cached in StudyCache::global() (sweep, compare-shift, sensitivity, optimize-lens)
// are returned from it when scene and parameters match; the result then has "cached": true.
std::optional<nlohmann::json> runAnalysis(const QString& id, const Scene& scene, const AnalysisParams& params,
                                          const StudyControl& control = {});

}  // namespace fovea::widgets

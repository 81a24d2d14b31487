#pragma once
// Shared plumbing of the study commands (sweep, compare-shift, sensitivity): tracer
// options, the on-disk result cache and the progress bar.

#include <functional>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "model/analysis/trace_evaluator.h"
#include "model/scene/scene.h"

namespace fovea::cli {

struct StudyCliOptions {
  int rays = 12000;
  double tolerance_deg = 3.0;
  std::string fov_method = "edges";  // edges (root-found field edges) or dense (the ray-count reference)
  bool no_cache = false;
};

void addStudyOptions(CLI::App* cmd, StudyCliOptions& options);

// The tracer-backed evaluator.
FovEvaluator studyEvaluator(const StudyCliOptions& options);

// Returns the cached result of (study, parameters, scene) or computes, stores and returns
// it. The key also holds this executable's identity (size, mtime), so a rebuilt binary
// never reuses older results. Cache directory: $FOVEA_CACHE_DIR, else
// $XDG_CACHE_HOME/fovea-studio/studies, else ~/.cache/fovea-studio/studies. The returned
// JSON gets "cached": true|false.
nlohmann::json cachedStudy(const std::string& study, const nlohmann::json& parameters, const Scene& scene,
                           const StudyCliOptions& options, const std::function<nlohmann::json()>& compute);

}  // namespace fovea::cli

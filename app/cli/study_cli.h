#pragma once
// Shared plumbing of the study commands (sweep, compare-shift, sensitivity, optimize-lens):
// the on-disk result cache, and running a registered analysis with the progress bar.

#include <functional>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "model/analysis/analysis_registry.h"
#include "model/scene/scene.h"

namespace fovea::cli {

// Adds --no-cache ("recompute even when an identical study is cached") to `cmd`.
void addNoCacheFlag(CLI::App* cmd, bool& no_cache);

// Returns the cached result of (study, parameters, scene) or computes, stores and returns
// it. The key also holds this executable's identity (size, mtime), so a rebuilt binary
// never reuses older results. Cache directory: $FOVEA_CACHE_DIR, else
// $XDG_CACHE_HOME/fovea-studio/studies, else ~/.cache/fovea-studio/studies. The returned
// JSON gets "cached": true|false.
nlohmann::json cachedStudy(const std::string& study, const nlohmann::json& parameters, const Scene& scene,
                           bool no_cache, const std::function<nlohmann::json()>& compute);

// Runs `def` on validated `values` with a progress bar labelled by its id. A parameter the
// scene refuses (std::invalid_argument "parameter: ...") exits 2 naming the flag; an
// analysis that cannot be computed for the scene exits 1.
nlohmann::json runStudy(const analysis::AnalysisDefinition& def, const Scene& scene, const nlohmann::json& values);

}  // namespace fovea::cli

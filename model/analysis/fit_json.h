#pragma once
// The JSON document of a fit (fovea-cli fit --json; the studio reads the same): docs/fitting.md.

#include <nlohmann/json.hpp>

#include "model/analysis/fit_solver.h"

namespace fovea {

nlohmann::json fitResultJson(const FitResult& r, const FitOptions& options);

}  // namespace fovea

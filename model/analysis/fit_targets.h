#pragma once
// A targets file for fitting a scene to measurements (docs/fitting.md): observables
// (fit_observables.h) with the value seen, its uncertainty and where it came from.
//
//   {"format": "fovea-fit-targets", "version": 1, "notes": "...",
//    "targets": [{"id": "fov-h-0", "observable": "fov_deg", "gaze_deg": 0, "direction": "horizontal",
//                 "value": 90.0, "sigma": 0.5, "unit": "deg", "source": "seed A.3 (simulated)"}, ...]}
// or just the list. Every other key of a target is a parameter of its observable. Unknown
// observables are refused with the list of known ones; "unit" must be the observable's.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "model/analysis/fit_observables.h"

namespace fovea {

// NOLINTNEXTLINE(bugprone-exception-escape): the implicit members copy json/strings; std::bad_alloc only.
struct FitTarget {
  std::string id, observable, unit, source;
  nlohmann::json parameters;  // the observable's parameters, defaults filled in
  double value = 0, sigma = 1;
};

inline constexpr const char* kFitTargetsFormat = "fovea-fit-targets";
// |value| <= 1e9 and 1e-9 <= sigma <= 1e9 (in the observable's unit): every residual and chi2 finite.
inline constexpr double kMaxFitTargetValue = 1e9;
inline constexpr double kMinFitTargetSigma = 1e-9;
// At most this many targets in a file.
inline constexpr std::size_t kMaxFitTargets = 100000;

// Throws std::invalid_argument naming the target (its id or index) and the key.
std::vector<FitTarget> parseFitTargets(const nlohmann::json& j);
// The file form (parseFitTargets reads it back to the same targets).
nlohmann::json fitTargetsJson(const std::vector<FitTarget>& targets, const std::string& notes = {});
// One target as an object of the file (its parameters inline).
nlohmann::json fitTargetJson(const FitTarget& t);

// A subset of the targets by a selection text: items separated by commas or spaces, each an id
// ("sim-xp-0"), a group prefix ending in '-' or '*' ("sim-", "meas-*": every id starting with
// it), or "all"; an item starting with '!' removes what it names. Empty or "all": every target.
// Order kept. Throws std::invalid_argument naming an item that matches nothing (with the
// groups the file has) and for an empty result.
std::vector<FitTarget> selectFitTargets(const std::vector<FitTarget>& targets, const std::string& selection);
// The groups of the ids ("sim-", "meas-": the text up to and including the first '-'), in order.
std::vector<std::string> fitTargetGroups(const std::vector<FitTarget>& targets);

// The model's value of every target for a scene, in order (one ObservableContext: shared
// x_p searches and sweeps are computed once). Throws std::runtime_error naming the target when
// the scene gives no value for it.
std::vector<double> evaluateTargets(const Scene& scene, const std::vector<FitTarget>& targets,
                                    const ObservableSettings& settings = {});

}  // namespace fovea

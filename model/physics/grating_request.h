#pragma once
// A planar-grating question as the CLI (`fovea-cli grating`, single or --batch) asks it, its
// validation, and its JSON forms. Model-independent: Kogelnik answers it here; other models
// (e.g. rigorous RCWA) take the same request and validation.

#include <optional>
#include <string>
#include <variant>

#include <nlohmann/json.hpp>

#include "model/physics/grating.h"

namespace fovea {

struct GratingRequest {
  PlanarGrating grating;           // n0 n1 thickness_um period_nm slant_deg probe_deg wavelength_nm polarization
  double absorption_per_mm = 0.0;  // intensity absorption coefficient of the film (Kogelnik's 2 alpha)
  std::string model = "kogelnik";
  std::optional<int> orders;  // rigorous models: Fourier orders -N..N (default: converged automatically)
  std::optional<int> slices;  // rigorous models: staircase slices M (default: converged automatically)
};

// The offending input by its JSON key ("thickness_um"); cliFlag() gives "--thickness-um".
struct GratingArgError {
  std::string key;
  std::string message;  // complete sentence naming the key, e.g. "n1: must be smaller than n0 (1.6 >= 1.5)"
};
std::string cliFlag(const std::string& key);

// Physical validity: finite numbers, n0 > 0, 0 <= n1 < n0, 0 <= thickness <= 10 m,
// wavelength > 0, period >= 1e-6 wavelengths (below, K^2 leaves the floating range long before
// the answer changes: the diffracted wave is evanescent from about lambda / (2 n0) down),
// |probe| < 90 deg (the probe enters through z = 0), absorption >= 0, orders in [0, 400],
// slices in [1, 2^24].
// `flags` = true names arguments as CLI flags (--n1), else as JSON keys (n1).
std::optional<GratingArgError> validateGratingRequest(const GratingRequest& r, bool flags);

// One JSON object (a --batch line). Required keys: n0 n1 thickness_um period_nm slant_deg
// probe_deg wavelength_nm; optional: polarization ("s" default), absorption_per_mm, model,
// orders, slices (integers). Unknown keys are ignored. Validation included. Messages quote at
// most a short excerpt of an offending value.
std::variant<GratingRequest, GratingArgError> gratingRequestFromJson(const nlohmann::json& j);

// The grating seen by a model: absorption_per_mm converted to Kogelnik's amplitude constant
// alpha = absorption / 2 in 1/µm (film.alpha_per_um of the request's grating is ignored).
PlanarGrating planarGratingOf(const GratingRequest& r);

// {"efficiency","type","nu","xi","diffracted_deg", ...extras} for the Kogelnik model. Throws
// std::domain_error when a number of the answer is not finite (never a null in a number field;
// diffracted_deg is null by contract when the diffracted wave is evanescent).
nlohmann::json kogelnikGratingJson(const GratingRequest& r);

// Throws std::domain_error naming the first key of `answer` whose number is NaN or infinite.
void requireFiniteNumbers(const nlohmann::json& answer, const GratingRequest& r);

}  // namespace fovea

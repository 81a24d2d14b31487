#pragma once
// RCWA answering the planar-grating question of `fovea-cli grating` (`--model
// rcwa`): Kogelnik's inputs (probe angle INSIDE the film, slant of K from the normal),
// plus the two outer media. Defaults: cover and substrate of index Re n0 (index-matched faces),
// so the inside angle is the outside angle and only the grating diffracts — the situation
// Kogelnik's theory describes. Give n_cover/n_substrate to include the film's faces.

#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "model/rigorous/rcwa.h"

namespace fovea::rigorous {

enum class GratingPolarization { S, P, Unpolarized };

struct RcwaGratingRequest {
  double n0 = 1.5, n1 = 0.0, thickness_um = 0.0, period_nm = 0.0, slant_deg = 0.0, probe_deg = 0.0, wavelength_nm = 0.0;
  GratingPolarization polarization = GratingPolarization::S;
  double absorption_per_mm = 0.0;     // intensity absorption of the film: Im n0 = α λ/(4π)
  std::optional<double> n_cover;      // default Re n0
  std::optional<double> n_substrate;  // default Re n0
  std::optional<int> orders;          // N (orders −N…N); default: chosen for `tolerance`
  std::optional<int> slices;          // M; default: chosen for `tolerance`
  double tolerance = 1e-4;            // on the efficiency of Kogelnik's diffracted wave
};

struct RcwaGratingAnswer {
  double efficiency = 0.0;  // Kogelnik's diffracted wave (order +1, or 0 reflected if K_x = 0)
  KogelnikOrder kogelnik_order;
  double total_efficiency = 0.0;
  std::vector<RcwaOrder> orders;  // propagating orders (s/p averaged when unpolarised)
  int orders_used = 0, slices_used = 0, solves = 0;
  bool converged = true;  // false when the automatic choice hit its limits
  double last_change = 0.0;
};

// Throws std::invalid_argument with a message naming the offending input (cover/substrate
// index, a probe the cover cannot launch, orders/slices out of range, …).
RcwaGratingAnswer solveRcwaGrating(const RcwaGratingRequest& request);

// {"efficiency", "total_efficiency", "orders":[{"order","side","efficiency","angle_deg"}],
//  "rcwa":{"orders","slices","converged","solves","kogelnik_order","kogelnik_side"}}
nlohmann::json rcwaAnswerJson(const RcwaGratingAnswer& answer);

}  // namespace fovea::rigorous

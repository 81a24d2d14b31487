#pragma once
// `fovea-cli grating --model rcwa`: the CLI's planar-grating request (model/physics/
// grating_request.h) answered by the rigorous coupled-wave solver (rcwa_grating.h), and the
// requests of the Kogelnik-vs-RCWA error map (kogelnik_vs_rcwa.h) as --batch lines, so that the
// map can be reproduced with the CLI alone (docs/benchmarks.md).

#include <vector>

#include <nlohmann/json.hpp>

#include "model/physics/grating_request.h"
#include "model/rigorous/kogelnik_vs_rcwa.h"

namespace fovea::rigorous {

// Kogelnik's JSON for the same request (type, nu, xi, c_r, c_s, diffracted_deg, … describe the
// geometry) with the answers replaced by RCWA's: efficiency (Kogelnik's diffracted wave),
// zero_order (transmitted order 0), model "rcwa"; plus kogelnik_efficiency, total_efficiency,
// orders [{order, side, efficiency, angle_deg}] and rcwa {orders, slices, converged, …}.
// Throws std::invalid_argument / std::domain_error for a request RCWA cannot evaluate.
nlohmann::json rcwaGratingJson(const GratingRequest& request);

// One --batch line per grid point: the request keys (full precision) plus "geometry" and
// "xi_target" (ignored by the batch reader).
std::vector<nlohmann::json> errorMapRequests(const KogelnikRcwaGrid& grid = {});

}  // namespace fovea::rigorous
